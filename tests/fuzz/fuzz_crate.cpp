// libFuzzer harness: the input is a whole .usdc crate file. Reading it must
// give a Layer or a UsdError, and a Layer read must write as usda or give a
// UsdError; limits are tighter than the defaults so that a run's memory
// stays under libFuzzer's -rss_limit_mb.
#include <cstddef>
#include <cstdint>
#include <span>

#include "usd/layer_io.h"
#include "usd/usda_writer.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  sdg::usd::ReadLimits limits;
  limits.maxArrayElements = uint64_t(1) << 22;
  limits.maxDecompressedBytes = uint64_t(64) << 20;
  limits.maxSpecs = uint64_t(1) << 20;
  try {
    sdg::usd::Layer layer = sdg::usd::readCrateLayer(std::span(data, size), "fuzz.usdc", limits);
    sdg::usd::writeUsdaLayer(layer, uint64_t(64) << 20);
  } catch (const sdg::usd::UsdError&) {
  }
  return 0;
}
