#include "assets/file_check.h"

#include <atomic>
#include <filesystem>
#include <fstream>

#include "assets/image.h"
#include "core/log.h"
#include "core/text.h"
#include "stage/prim_types.h"

namespace sdg {
namespace fs = std::filesystem;

namespace {

bool namesFiles(const AttributeSpec& spec) {
  if (spec.type == ValueType::Asset || spec.type == ValueType::AssetArray) return true;
  return spec.type == ValueType::String && spec.files != FileKind::None;
}

std::string lowerExtension(const std::string& file) {
  std::string ext = fs::path(file).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// Whether the image's header reads: any format OpenImageIO reads, within
// the size limits. Only the header is read, so `validate` stays fast.
std::optional<std::string> imageProblem(const std::string& file, const std::string& path) {
  try {
    readImageHeader(path);
    return std::nullopt;
  } catch (const RunError& e) {
    std::string why = e.what();
    if (why.starts_with(path + ": ")) why.erase(0, path.size() + 2);  // the path is said once, below
    return "texture " + text::quote(file) + " (" + path + "): " + why;
  }
}

void warnIsaacDefaultsSkipped(const std::string& owner) {
  static std::atomic<bool> warned{false};
  if (warned.exchange(true)) return;
  log::warn(owner + ": Isaac Sim's default assets (/Isaac/...) are skipped: no Isaac asset root is set. To use "
                    "them, point --isaac-assets DIR, SDGBEHAVE_ISAAC_ASSETS or the scene's isaac_assets: at a local "
                    "copy of Isaac Sim's asset pack (the folder that holds Isaac/)");
}

}  // namespace

const char* fileKindNoun(FileKind kind) {
  switch (kind) {
    case FileKind::Mesh: return "mesh";
    case FileKind::Image: return "texture";
    default: return "file";
  }
}

std::vector<std::string> fileEntriesOf(const Attribute& attr, const AttributeSpec& spec, const AssetResolver& resolver,
                                       const std::string& owner) {
  std::vector<std::string> entries;
  switch (attr.value.type()) {
    case ValueType::Asset:
      if (!attr.value.get<std::string>().empty()) entries.push_back(attr.value.get<std::string>());
      break;
    case ValueType::AssetArray:
      for (const std::string& s : attr.value.get<std::vector<std::string>>())
        if (!s.empty()) entries.push_back(s);
      break;
    case ValueType::String:
      if (spec.files != FileKind::None) entries = text::splitCsv(attr.value.get<std::string>());
      break;
    default: break;
  }
  // A default nobody wrote that points into Isaac's asset pack, while no
  // local copy of that pack is configured, would fail every run of every
  // scene that does not override it: leave it out and say how to get it.
  if (!attr.loc.known() && resolver.isaacRoot().empty()) {
    size_t before = entries.size();
    std::erase_if(entries, [](const std::string& e) { return isIsaacAssetPath(e); });
    if (entries.size() != before) warnIsaacDefaultsSkipped(owner);
  }
  return entries;
}

std::optional<std::string> fileProblem(const std::string& entry, FileKind kind, const AssetResolver& resolver) {
  std::string file = entry;
  if (kind == FileKind::Mesh) file = file.substr(0, file.rfind('#'));
  const std::string noun = fileKindNoun(kind);
  if (file.find("://") != std::string::npos)
    return noun + " " + text::quote(file) + " is a URL; sdgbehave reads local files only";
  const std::string ext = lowerExtension(file);
  if (kind == FileKind::Mesh && ext.starts_with(".usd"))
    return noun + " " + text::quote(file) + " is a USD file, which sdgbehave cannot read; convert it to glTF, OBJ, " +
           "FBX, PLY, STL or DAE (for example with Blender) and name that file instead";
  std::optional<std::string> path = resolver.resolve(file);
  if (!path) {
    std::string why = noun + " " + text::quote(file) + " not found; " + resolver.describeSearch(file);
    if (isIsaacAssetPath(file) && resolver.isaacRoot().empty())
      why += " (Isaac Sim asset paths resolve against --isaac-assets DIR, SDGBEHAVE_ISAAC_ASSETS or the scene's "
             "isaac_assets:, and none is set)";
    return why;
  }
  std::ifstream probe(*path, std::ios::binary);
  if (!probe || probe.peek() == std::ifstream::traits_type::eof())
    return noun + " " + text::quote(file) + " (" + *path + ") cannot be read" + (probe ? ": it is empty" : "");
  if (kind == FileKind::Image) return imageProblem(file, *path);
  return std::nullopt;
}

void forEachStageFile(const Stage& stage, const BehaviorCatalog& catalog, const AssetResolver& resolver,
                      const StageFileVisitor& visit) {
  auto visitAttribute = [&](const Prim& prim, const std::string& name, const AttributeSpec& spec) {
    const Attribute* attr = prim.findAttribute(name);
    if (!attr) return;
    const std::string owner = prim.path() + "." + name;
    const FileKind kind = spec.files == FileKind::None ? FileKind::Any : spec.files;
    for (const std::string& entry : fileEntriesOf(*attr, spec, resolver, owner)) visit(prim, *attr, owner, entry, kind);
  };
  stage.traverse([&](const Prim& prim) {
    for (const AttributeSpec& spec : primTypeInfo(prim.type()).attributes)
      if (namesFiles(spec)) visitAttribute(prim, spec.name, spec);
    for (const std::string& behavior : prim.behaviors())
      if (const BehaviorSpec* b = catalog.find(behavior))
        for (const AttributeSpec& spec : b->variables)
          if (namesFiles(spec)) visitAttribute(prim, exposedAttributeName(behavior, spec.name), spec);
  });
}

void checkStageFiles(const Stage& stage, const BehaviorCatalog& catalog, const AssetResolver& resolver,
                     Diagnostics& diag) {
  forEachStageFile(stage, catalog, resolver,
                   [&](const Prim& prim, const Attribute& attr, const std::string& owner, const std::string& entry,
                       FileKind kind) {
                     if (std::optional<std::string> problem = fileProblem(entry, kind, resolver))
                       diag.error(attr.loc.known() ? attr.loc : prim.loc(), owner + ": " + *problem);
                   });
}

}  // namespace sdg
