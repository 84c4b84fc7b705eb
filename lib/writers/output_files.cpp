#include "writers/output_files.h"

#include <cstdio>
#include <filesystem>

#include "core/diagnostics.h"
#include "core/file_io.h"

namespace sdg {
namespace fs = std::filesystem;

namespace {
std::string fragmentPath(const char* kind, uint64_t frame, size_t product) {
  char name[64];
  std::snprintf(name, sizeof name, "%s/%s/%012llu_%03zu.json", kPartsFolder, kind,
                static_cast<unsigned long long>(frame), product);
  return name;
}
}  // namespace

std::string cocoFragmentPath(uint64_t frame, size_t product) { return fragmentPath("coco", frame, product); }
std::string bopFragmentPath(uint64_t frame, size_t product) { return fragmentPath("bop", frame, product); }

std::string contactSheetTilePath(uint64_t frame) {
  char name[64];
  std::snprintf(name, sizeof name, "%s/contact_sheet/%012llu.png", kPartsFolder, static_cast<unsigned long long>(frame));
  return name;
}

void createParentFolder(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw RunError("cannot create " + parent.string() + ": " + ec.message());
}

void writeFiles(const std::string& dir, const std::vector<OutputFile>& files) {
  for (const OutputFile& file : files) {
    fs::path path = fs::path(dir) / file.path;
    createParentFolder(path.string());
    writeFileAtomic(path.string(), file.bytes);
  }
}

}  // namespace sdg
