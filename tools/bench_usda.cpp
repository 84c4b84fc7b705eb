// Measures the usda parser's throughput (MB/s) and composition's on a
// generated layer shaped like real exports: many Xform/Mesh prims, each
// mesh with points, normals, UVs and index arrays, primvars with
// metadata, material bindings, and a few thousand small prims with
// metadata and time samples.
//
//   sdg_bench_usda [megabytes=64] [repeats=3]
//
// Prints the best of the repeats (the machine is shared: the best run is
// the one least disturbed).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "usd/compose.h"
#include "usd/layer_io.h"

namespace {

// Deterministic pseudo-random numbers with the digits real files carry.
struct Numbers {
  uint64_t state = 0x9e3779b97f4a7c15ull;
  double next() {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return static_cast<double>(state % 2000000) / 1000000.0 - 1.0;
  }
};

void appendFloat(std::string& out, double v) {
  char buf[32];
  int n = std::snprintf(buf, sizeof buf, "%.7g", v);
  out.append(buf, static_cast<size_t>(n));
}

void appendTuples(std::string& out, Numbers& rng, int count, int width) {
  out += '[';
  for (int i = 0; i < count; ++i) {
    if (i) out += ", ";
    out += '(';
    for (int c = 0; c < width; ++c) {
      if (c) out += ", ";
      appendFloat(out, rng.next());
    }
    out += ')';
  }
  out += ']';
}

std::string generate(size_t targetBytes) {
  Numbers rng;
  std::string out = "#usda 1.0\n(\n    defaultPrim = \"World\"\n    metersPerUnit = 0.01\n    upAxis = \"Z\"\n"
                    "    startTimeCode = 0\n    endTimeCode = 100\n)\n\ndef Xform \"World\" (\n    kind = \"assembly\"\n)\n{\n";
  out += "    def Scope \"Looks\"\n    {\n        def Material \"Mat\"\n        {\n"
         "            token outputs:surface.connect = </World/Looks/Mat/Shader.outputs:surface>\n"
         "            def Shader \"Shader\"\n            {\n                uniform token info:id = \"UsdPreviewSurface\"\n"
         "                color3f inputs:diffuseColor = (0.8, 0.2, 0.1)\n                token outputs:surface\n"
         "            }\n        }\n    }\n";
  for (int part = 0; out.size() < targetBytes; ++part) {
    std::string name = "Part_" + std::to_string(part);
    out += "    def Xform \"" + name + "\" (\n        prepend apiSchemas = [\"MaterialBindingAPI\"]\n"
           "        customData = { string source = \"bench\"; int index = " + std::to_string(part) + " }\n    )\n    {\n";
    out += "        double3 xformOp:translate.timeSamples = {\n            0: (0, 0, 0),\n            100: (";
    appendFloat(out, rng.next());
    out += ", 1, 2),\n        }\n        float3 xformOp:rotateXYZ = (0, 45, 0)\n"
           "        uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:rotateXYZ\"]\n";
    out += "        def Mesh \"Geom\"\n        {\n            int[] faceVertexCounts = [";
    const int faces = 500, points = 520;
    for (int f = 0; f < faces; ++f) out += f ? ", 4" : "4";
    out += "]\n            int[] faceVertexIndices = [";
    for (int i = 0; i < faces * 4; ++i) {
      if (i) out += ", ";
      out += std::to_string((i * 7 + part) % points);
    }
    out += "]\n            point3f[] points = ";
    appendTuples(out, rng, points, 3);
    out += "\n            normal3f[] normals = ";
    appendTuples(out, rng, faces * 4, 3);
    out += " (\n                interpolation = \"faceVarying\"\n            )\n            texCoord2f[] primvars:st = ";
    appendTuples(out, rng, faces * 4, 2);
    out += " (\n                interpolation = \"faceVarying\"\n            )\n"
           "            rel material:binding = </World/Looks/Mat>\n            uniform token subdivisionScheme = \"none\"\n"
           "        }\n    }\n";
  }
  out += "}\n";
  return out;
}

template <class Fn>
double bestSeconds(int repeats, Fn&& fn) {
  double best = 1e300;
  for (int i = 0; i < repeats; ++i) {
    auto start = std::chrono::steady_clock::now();
    fn();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  size_t megabytes = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 64;
  int repeats = argc > 2 ? std::atoi(argv[2]) : 3;
  std::string text = generate(megabytes << 20);
  double mb = static_cast<double>(text.size()) / (1 << 20);
  size_t specs = 0;
  double parse = bestSeconds(repeats, [&] { specs = sdg::usd::readUsdaLayer(text, "bench.usda").specs.size(); });
  sdg::usd::Layer layer = sdg::usd::readUsdaLayer(text, "bench.usda");
  sdg::usd::LayerReader reader = [&](const std::string&) { return layer; };
  size_t prims = 0;
  double compose = bestSeconds(repeats, [&] { prims = sdg::usd::composeStage("bench.usda", reader).prims.size(); });
  std::printf("usda: %.1f MB, %zu specs: parsed in %.3f s = %.1f MB/s (best of %d)\n", mb, specs, parse, mb / parse, repeats);
  std::printf("compose: %zu prims in %.3f s (the layer copied in, values resolved)\n", prims, compose);
  return 0;
}
