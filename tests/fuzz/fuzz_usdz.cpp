// libFuzzer harness: the input is a .usdz package. Open it, read every
// entry (crate layers through the crate reader), resolve an asset path from
// each: a result or a UsdError, nothing else.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "usd/layer_io.h"
#include "usd/usdz_package.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  sdg::usd::ReadLimits limits;
  limits.maxFileBytes = uint64_t(16) << 20;
  limits.maxArrayElements = uint64_t(1) << 22;
  limits.maxDecompressedBytes = uint64_t(64) << 20;
  limits.maxNesting = 8;
  try {
    sdg::usd::UsdzPackage package(std::vector<uint8_t>(data, data + size), "fuzz.usdz", limits);
    for (const auto& entry : package.entries()) {
      package.resolve(entry, "../0/texture.png");
      try {
        auto bytes = package.read(entry);
        if (bytes.size() >= 8 && std::memcmp(bytes.data(), "PXR-USDC", 8) == 0)
          sdg::usd::readCrateLayer(bytes, "fuzz.usdz[" + entry + "]", limits);
      } catch (const sdg::usd::UsdError&) {
      }
    }
  } catch (const sdg::usd::UsdError&) {
  }
  return 0;
}
