// libFuzzer harness: arbitrary bytes as a usda layer, parsed and then
// composed (internal arcs, variants and classes only: any other layer is
// missing). Only UsdError may come out; anything else is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "usd/compose.h"
#include "usd/layer_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text = "#usda 1.0\n";
  text.append(reinterpret_cast<const char*>(data), size);
  sdg::usd::ReadLimits limits;
  limits.maxArrayElements = 1 << 16;
  limits.maxSpecs = 1 << 14;
  try {
    sdg::usd::Layer layer = sdg::usd::readUsdaLayer(text, "fuzz.usda", limits);
    sdg::usd::LayerReader reader = [&](const std::string& identifier) {
      if (identifier != "fuzz.usda") throw sdg::usd::UsdError(sdg::SourceLoc(identifier, 0, 0), "missing");
      return layer;
    };
    sdg::usd::ComposeOptions options;
    options.limits.maxPrims = 1 << 14;
    options.limits.maxArcsPerPrim = 256;
    sdg::usd::composeStage("fuzz.usda", reader, options);
  } catch (const sdg::usd::UsdError&) {
  }
  return 0;
}
