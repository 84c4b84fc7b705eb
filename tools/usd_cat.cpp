// Prints any USD layer as usda text (as Pixar's usdcat does): a .usda,
// .usdc or .usd file, a .usdz package's root layer, or a package entry
// "pkg.usdz[inner.usdc]". A layer that cannot be read exits 2 with the
// reader's message (file and section or line:col).
//
//   sdg_usd_cat FILE [-o OUT.usda]
#include <cstdio>
#include <fstream>
#include <string>

#include "usd/layer_io.h"
#include "usd/usda_writer.h"

int main(int argc, char** argv) {
  std::string input, output;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "-o" && i + 1 < argc) {
      output = argv[++i];
    } else if (input.empty() && arg[0] != '-') {
      input = arg;
    } else {
      input.clear();
      break;
    }
  }
  if (input.empty()) {
    std::fprintf(stderr, "usage: %s FILE.usd[a|c|z] [-o OUT.usda]\n", argv[0]);
    return 2;
  }
  try {
    std::string text = sdg::usd::writeUsdaLayer(sdg::usd::readLayerFile(input));
    if (output.empty()) {
      std::fwrite(text.data(), 1, text.size(), stdout);
    } else if (!(std::ofstream(output, std::ios::binary) << text)) {
      std::fprintf(stderr, "%s: cannot write the file\n", output.c_str());
      return 1;
    }
  } catch (const sdg::usd::UsdError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
  return 0;
}
