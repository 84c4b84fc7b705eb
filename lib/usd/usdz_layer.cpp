// readPackagedLayer (usdz_package.h): one layer of a .usdz package, crate or
// usda told apart by its first bytes as USD's .usd files are.
#include <cstring>

#include "usd/layer_io.h"
#include "usd/usdz_package.h"

namespace sdg::usd {

Layer readPackagedLayer(const std::string& packagePath, const std::string& entry, const ReadLimits& limits) {
  UsdzPackage package(packagePath, limits);
  std::string name = entry.empty() ? package.firstLayer() : entry;
  if (name.empty())
    throw usdErrorAt(SourceLoc(packagePath, 0, 0), "usdz package: holds no .usd, .usda or .usdc layer");
  std::vector<uint8_t> bytes = package.read(name);
  const std::string identifier = packagePath + "[" + name + "]";
  Layer layer;
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), "PXR-USDC", 8) == 0) {
    layer = readCrateLayer(bytes, identifier, limits);
  } else if (bytes.size() >= 5 && std::memcmp(bytes.data(), "#usda", 5) == 0) {
    layer = readUsdaLayer(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), identifier,
                          limits);
  } else {
    throw usdErrorAt(SourceLoc(identifier, 0, 0), "neither a crate layer (\"PXR-USDC\") nor a usda layer (\"#usda\")");
  }
  layer.identifier = identifier;
  layer.realPath = packagePath;
  return layer;
}

}  // namespace sdg::usd
