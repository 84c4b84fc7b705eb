// readLayerFile: any layer file, told apart by its first bytes — text
// ("#usda"), binary crate ("PXR-USDC") or a usdz package (a zip, "PK\3\4"),
// and package entries named "pkg.usdz[inner/path]". Kept apart from
// layer_io.cpp because it needs the crate and package readers, which are
// built in their own branch: lib/CMakeLists.txt adds this file with them.
#include "usd/layer_io.h"

#include "core/git_lfs.h"

namespace sdg::usd {

Layer readLayerFile(const std::string& path, const ReadLimits& limits) {
  auto [package, entry] = splitPackagePath(path);
  if (!entry.empty()) return readPackagedLayer(package, entry, limits);
  std::string bytes = readFileBytes(path, limits);
  if (bytes.compare(0, 4, "PK\x03\x04") == 0) return readPackagedLayer(path, "", limits);
  if (isGitLfsPointer(bytes)) throw gitLfsPointerError(path);
  Layer layer;
  if (bytes.compare(0, 8, "PXR-USDC") == 0) {
    layer = readCrateLayer(std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()),
                           path, limits);
  } else if (bytes.compare(0, 5, "#usda") == 0) {
    layer = readUsdaLayer(bytes, path, limits);
  } else {
    throw usdErrorAt(SourceLoc(path, 0, 0),
                     "not a USD layer: expected '#usda' (text), 'PXR-USDC' (crate) or a usdz package");
  }
  layer.realPath = path;
  return layer;
}

}  // namespace sdg::usd
