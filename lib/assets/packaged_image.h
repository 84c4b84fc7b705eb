#pragma once
// Textures inside a .usdz package, named as USD's asset paths resolve them:
// "dir/pkg.usdz[textures/wood.png]" (lib/usd's package-relative form). The
// image readers read files, so these hand them the entry's bytes instead.
#include <cstdint>
#include <string>
#include <vector>

#include "assets/asset_resolver.h"

namespace sdg {

// True for "pkg.usdz[entry]".
bool isPackagedAssetPath(const std::string& path);

// The bytes of the entry; the package file is found through `resolver`.
// Throws RunError naming the path for a missing package or entry.
std::vector<uint8_t> readPackagedAsset(const std::string& path, const AssetResolver& resolver);

}  // namespace sdg
