#include "run/dataset_finalize.h"

#include <filesystem>

#include "core/diagnostics.h"
#include "core/file_io.h"
#include "writers/bop_writer.h"
#include "writers/coco_writer.h"
#include "writers/contact_sheet.h"
#include "writers/manifest.h"

namespace sdg {
namespace fs = std::filesystem;

namespace {
constexpr const char* kContactSheetFile = "contact_sheet.png";
}  // namespace

FinalizeResult finalizeDataset(const std::string& dir, const RunInfo& info) {
  // The manifests' lines are indexed, not held: finishing uses the same
  // memory after 100,000 frames as after 100.
  const ManifestIndex manifest = indexManifests(dir);
  const std::vector<ManifestIndex::Line>& entries = manifest.lines;
  // Every (frame, product) of the run must be there, exactly once.
  size_t at = 0;
  for (uint64_t frame = 0; frame < info.frames(); ++frame)
    for (uint32_t product = 0; product < info.products.size(); ++product, ++at)
      if (at >= entries.size() || entries[at].frame != frame || entries[at].product != product)
        throw RunError(dir + ": frame " + std::to_string(frame) + " of " + info.products[product] +
                       " is not in the manifest; run the shard that owns it (with --resume) and merge again");
  if (entries.size() != at)
    throw RunError(dir + ": the manifest lists frames beyond the run's " + std::to_string(info.frames()));
  FinalizeResult result;
  result.frames = info.frames();
  if (!info.cocoFile.empty()) {
    std::vector<std::string> fragments;
    for (uint64_t frame = 0; frame < info.frames(); ++frame)
      for (size_t product = 0; product < info.products.size(); ++product)
        fragments.push_back((fs::path(dir) / cocoFragmentPath(frame, product)).string());
    assembleCoco((fs::path(dir) / info.cocoFile).string(), info.cocoTaxonomy, fragments);
    ++result.files;
  }
  if (!info.bopSplit.empty())
    result.files += assembleBopScenes(dir, info.bopSplit, info.iterations, info.framesPerIteration, info.products.size());
  if (info.contactSheet && info.frames() > 0) {
    std::vector<std::string> tiles;
    for (uint64_t frame : contactSheetFrames(info.frames()))
      tiles.push_back((fs::path(dir) / contactSheetTilePath(frame)).string());
    writeFileAtomic((fs::path(dir) / kContactSheetFile).string(), composeContactSheet(tiles));
    ++result.files;
  }
  writeCanonicalManifest(dir, manifest);
  ++result.files;
  return result;
}

void writeContactSheetOfFinishedFrames(const std::string& dir, const RunInfo& info) {
  std::vector<std::string> tiles;
  std::error_code ec;
  for (uint64_t frame : contactSheetFrames(info.frames())) {
    const fs::path tile = fs::path(dir) / contactSheetTilePath(frame);
    if (fs::is_regular_file(tile, ec)) tiles.push_back(tile.string());
  }
  if (!tiles.empty()) writeFileAtomic((fs::path(dir) / kContactSheetFile).string(), composeContactSheet(tiles));
}

}  // namespace sdg
