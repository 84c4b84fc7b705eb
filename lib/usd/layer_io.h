#pragma once
// Reading USD layers from files and memory, whatever their form:
//   .usda  text (usda_reader.h)
//   .usdc  binary crate (crate_reader.h)
//   .usd   either, told apart by the first bytes ("PXR-USDC" or "#usda")
//   .usdz  a zip package of stored entries (usdz_package.h): its first
//          layer is the root; asset paths inside resolve inside the package
// Every function throws UsdError naming the file (and line:col or section).
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "usd/layer.h"

namespace sdg::usd {

// The text parser: `identifier` names the file in errors and in Layer.
Layer readUsdaLayer(std::string_view text, const std::string& identifier, const ReadLimits& limits = {});

// The crate reader (bytes of a whole .usdc file or package entry).
Layer readCrateLayer(std::span<const uint8_t> bytes, const std::string& identifier,
                     const ReadLimits& limits = {});

// Reads the layer at `path`: a .usda/.usdc/.usd file, a .usdz package (its
// root layer) or a package entry "pkg.usdz[inner/path.usdc]".
Layer readLayerFile(const std::string& path, const ReadLimits& limits = {});

}  // namespace sdg::usd
