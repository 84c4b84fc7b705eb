#pragma once
// A frame's files as writers hand them over (paths relative to the output
// folder), where the hidden parts of a frame go (.sdgbehave/: COCO and BOP
// fragments, contact sheet tiles), and how files reach the disk: each under
// a temporary name, renamed when complete.
#include <cstdint>
#include <string>
#include <vector>

namespace sdg {

inline constexpr const char* kPartsFolder = ".sdgbehave";

struct OutputFile {
  std::string path;  // relative to the output folder
  std::vector<uint8_t> bytes;
};

std::string cocoFragmentPath(uint64_t frame, size_t product);  // relative
std::string bopFragmentPath(uint64_t frame, size_t product);   // relative
std::string contactSheetTilePath(uint64_t frame);              // relative

// Creates the folders above `path`; RunError when it cannot.
void createParentFolder(const std::string& path);
// Writes files (paths relative to `dir`) atomically (a temporary renamed
// into place) without syncing: a frame's files become durable with the
// manifest's next batch (writers/manifest.h, group commit).
void writeFiles(const std::string& dir, const std::vector<OutputFile>& files);

}  // namespace sdg
