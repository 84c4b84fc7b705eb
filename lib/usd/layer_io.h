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
#include <utility>
#include <string_view>

#include "usd/layer.h"

namespace sdg::usd {

// The text parser: `identifier` names the file in errors and in Layer.
Layer readUsdaLayer(std::string_view text, const std::string& identifier, const ReadLimits& limits = {});

// The crate reader (bytes of a whole .usdc file or package entry).
Layer readCrateLayer(std::span<const uint8_t> bytes, const std::string& identifier,
                     const ReadLimits& limits = {});

// Reads the layer at `path`: a .usda/.usdc/.usd file, a .usdz package (its
// root layer) or a package entry "pkg.usdz[inner/path.usdc]". Defined in
// layer_io_binary.cpp, which needs the crate reader and the package reader.
Layer readLayerFile(const std::string& path, const ReadLimits& limits = {});

// The layer `entry` of the .usdz package at `packagePath` ("" = the
// package's root layer, its first entry). Defined by the package reader.
Layer readPackagedLayer(const std::string& packagePath, const std::string& entry, const ReadLimits& limits = {});

// The whole file (UsdError naming the file when it cannot be read or is
// larger than limits.maxFileBytes).
std::string readFileBytes(const std::string& path, const ReadLimits& limits = {});

// A text layer file: .usda, or .usd whose first bytes are "#usda". A binary
// file is a UsdError saying so (readLayerFile reads those).
Layer readTextLayerFile(const std::string& path, const ReadLimits& limits = {});

// A UsdError for a layer file that is a Git LFS pointer (core/git_lfs.h):
// located at the file, its message naming the file ("x.usd is a Git LFS
// pointer, not a USD layer: run git lfs pull ...").
UsdError gitLfsPointerError(const std::string& path);

// "pkg.usdz[inner/a.usdc]" -> {"pkg.usdz", "inner/a.usdc"}; a plain path
// gives {path, ""}. Nested packages ("a.usdz[b.usdz[c.usda]]") split at the
// outermost brackets.
std::pair<std::string, std::string> splitPackagePath(const std::string& path);

}  // namespace sdg::usd
