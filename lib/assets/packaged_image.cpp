#include "assets/packaged_image.h"

#include "core/diagnostics.h"
#include "usd/layer_io.h"
#include "usd/usdz_package.h"

namespace sdg {

bool isPackagedAssetPath(const std::string& path) {
  const size_t open = path.find(".usdz[");
  return open != std::string::npos && path.ends_with("]");
}

std::vector<uint8_t> readPackagedAsset(const std::string& path, const AssetResolver& resolver) {
  auto [package, entry] = usd::splitPackagePath(path);
  std::optional<std::string> file = resolver.resolve(package);
  if (!file) throw RunError("package " + package + " of '" + path + "' not found; " + resolver.describeSearch(package));
  try {
    return usd::UsdzPackage(*file).read(entry);
  } catch (const usd::UsdError& e) {
    throw RunError(path + ": " + e.what());
  }
}

}  // namespace sdg
