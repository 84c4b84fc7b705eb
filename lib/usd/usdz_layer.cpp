// readPackagedLayer (usdz_package.h): one layer of a .usdz package, crate or
// usda told apart by its first bytes as USD's .usd files are. An entry that
// is itself a package ("a.usdz[b.usdz]", as a reference to a nested package
// names it) gives that package's root layer, "a.usdz[b.usdz[root.usdc]]".
#include <cstring>
#include <memory>

#include "core/git_lfs.h"
#include "usd/asset_paths.h"
#include "usd/layer_io.h"
#include "usd/usdz_package.h"

namespace sdg::usd {

namespace {

bool isZip(const std::vector<uint8_t>& bytes) { return bytes.size() >= 4 && std::memcmp(bytes.data(), "PK\x03\x04", 4) == 0; }

}  // namespace

Layer readPackagedLayer(const std::string& packagePath, const std::string& entry, const ReadLimits& limits) {
  UsdzPackage package(packagePath, limits);
  std::string name = entry.empty() ? package.firstLayer() : entry;
  if (name.empty())
    throw usdErrorAt(SourceLoc(packagePath, 0, 0), "usdz package: holds no .usd, .usda or .usdc layer");
  std::vector<uint8_t> bytes = package.read(name);
  std::string identifier = joinPackagePath(packagePath, name);
  // A nested package: its root layer, to the nesting limit.
  std::unique_ptr<UsdzPackage> nested;
  for (uint32_t depth = 0; isZip(bytes); ++depth) {
    if (depth >= limits.maxNesting)
      throw usdErrorAt(SourceLoc(identifier, 0, 0), "usdz package: packages nest deeper than the limit");
    nested = std::make_unique<UsdzPackage>(std::move(bytes), identifier, limits);
    const std::string root = nested->firstLayer();
    if (root.empty()) throw usdErrorAt(SourceLoc(identifier, 0, 0), "usdz package: holds no .usd, .usda or .usdc layer");
    bytes = nested->read(root);
    identifier = joinPackagePath(identifier, root);
  }
  Layer layer;
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), "PXR-USDC", 8) == 0) {
    layer = readCrateLayer(bytes, identifier, limits);
  } else if (bytes.size() >= 5 && std::memcmp(bytes.data(), "#usda", 5) == 0) {
    layer = readUsdaLayer(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), identifier,
                          limits);
  } else if (isGitLfsPointer(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()))) {
    throw gitLfsPointerError(identifier);
  } else {
    throw usdErrorAt(SourceLoc(identifier, 0, 0), "neither a crate layer (\"PXR-USDC\") nor a usda layer (\"#usda\")");
  }
  layer.identifier = identifier;
  layer.realPath = packagePath;
  return layer;
}

}  // namespace sdg::usd
