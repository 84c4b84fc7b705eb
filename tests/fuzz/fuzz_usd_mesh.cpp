// libFuzzer harness: a usda Mesh whose topology and primvars come from the
// fuzz input (face counts and indices around and beyond the valid range,
// points including nan, inf and values past float's range, normals, st,
// displayColor and displayOpacity of every interpolation, indexed or not,
// a GeomSubset with a material binding), imported onto a stage
// (importUsdPrims) and every Mesh prim then triangulated as the renderer
// does. The text is well formed, so the fuzzer spends its time on the
// mesh import rather than on the usda parser (fuzz_usda's job). Only
// SceneError (the located exit 2) and RunError may come out; a crash,
// sanitizer report or leak is a finding. It finds the negative
// faceVertexCounts crash of the import before usd_mesh_topology.h.
#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "assets/inline_mesh.h"
#include "core/diagnostics.h"
#include "scene_io/usd_import.h"
#include "usd/compose.h"
#include "usd/layer_io.h"

namespace {

// An integer that is mostly small (counts and indices a mesh of a few
// points uses) and sometimes an extreme one; past int32 only when `wide`
// (the usda reader refuses those in an int[]).
int64_t integer(FuzzedDataProvider& in, bool wide) {
  static constexpr int64_t kExtremes[] = {-1, std::numeric_limits<int32_t>::min(), std::numeric_limits<int32_t>::max(),
                                          int64_t(1) << 31, int64_t(1) << 40, -(int64_t(1) << 40)};
  if (in.ConsumeIntegralInRange<int>(0, 15) == 0)
    return kExtremes[in.ConsumeIntegralInRange<size_t>(0, std::size(kExtremes) - (wide ? 1 : 4))];
  return in.ConsumeIntegralInRange<int64_t>(-3, 12);
}

std::string number(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange<int>(0, 12)) {
    case 0: return "nan";
    case 1: return "inf";
    case 2: return "-inf";
    case 3: return "1e39";  // finite as a double, infinite as a float
    default: {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.6g", double(in.ConsumeIntegralInRange<int>(-1000, 1000)) / 100.0);
      return buf;
    }
  }
}

// "int[] name = [...]", sometimes authored as int64[] or double[] (wrong
// types a file may hold: their values reach the import as they are).
std::string intArray(FuzzedDataProvider& in, const std::string& name, size_t maxItems) {
  static const char* kTypes[] = {"int[]", "int[]", "int64[]", "double[]"};
  const std::string type = kTypes[in.ConsumeIntegralInRange<size_t>(0, std::size(kTypes) - 1)];
  std::string out = type + " " + name + " = [";
  const size_t n = in.ConsumeIntegralInRange<size_t>(0, maxItems);
  for (size_t i = 0; i < n; ++i) {
    out += (i ? ", " : "") + std::to_string(integer(in, type != "int[]"));
    if (type == "double[]" && in.ConsumeIntegralInRange<int>(0, 7) == 0) out += ".5";
  }
  return out + "]\n";
}

// An array of `width`-tuples ("[(1, 2), ...]", or plain numbers for width 1).
std::string tupleArray(FuzzedDataProvider& in, int width, size_t maxItems) {
  std::string out = "[";
  const size_t n = in.ConsumeIntegralInRange<size_t>(0, maxItems);
  for (size_t i = 0; i < n; ++i) {
    out += i ? ", " : "";
    if (width == 1) {
      out += number(in);
      continue;
    }
    out += "(";
    for (int k = 0; k < width; ++k) out += (k ? ", " : "") + number(in);
    out += ")";
  }
  return out + "]";
}

// A primvar of a fuzzed interpolation (or none), maybe indexed.
void primvar(FuzzedDataProvider& in, std::string& text, const char* type, const char* name, int width) {
  if (!in.ConsumeBool()) return;
  static const char* kInterpolations[] = {"", "constant", "uniform", "vertex", "varying", "faceVarying", "perFace"};
  const char* interpolation = kInterpolations[in.ConsumeIntegralInRange<size_t>(0, std::size(kInterpolations) - 1)];
  text += std::string("    ") + type + " " + name + " = " + tupleArray(in, width, 24);
  if (*interpolation) text += std::string(" (\n        interpolation = \"") + interpolation + "\"\n    )";
  text += "\n";
  if (in.ConsumeBool()) text += "    " + intArray(in, std::string(name) + ":indices", 24);
}

std::string meshLayer(FuzzedDataProvider& in) {
  std::string text = "#usda 1.0\n(\n    defaultPrim = \"M\"\n)\n\ndef Mesh \"M\"\n{\n";
  text += "    point3f[] points = " + tupleArray(in, 3, 12) + "\n";
  text += "    " + intArray(in, "faceVertexCounts", 8);
  text += "    " + intArray(in, "faceVertexIndices", 32);
  primvar(in, text, "normal3f[]", "normals", 3);
  primvar(in, text, "normal3f[]", "primvars:normals", 3);
  primvar(in, text, "texCoord2f[]", "primvars:st", 2);
  primvar(in, text, "texCoord2f[]", "primvars:uv1", 2);
  primvar(in, text, "color3f[]", "primvars:displayColor", 3);
  primvar(in, text, "float[]", "primvars:displayOpacity", 1);
  if (in.ConsumeBool()) text += "    uniform token subdivisionScheme = \"none\"\n";
  if (in.ConsumeBool()) text += "    uniform token orientation = \"leftHanded\"\n";
  static const char* kElementTypes[] = {"uniform token elementType = \"face\"", "uniform token elementType = \"point\"",
                                        "int elementType = 1", ""};
  for (int s = in.ConsumeIntegralInRange<int>(0, 2); s > 0; --s)
    text += "    def GeomSubset \"S" + std::to_string(s) + "\"\n    {\n        " +
            kElementTypes[in.ConsumeIntegralInRange<size_t>(0, std::size(kElementTypes) - 1)] + "\n        " +
            intArray(in, "indices", 6) + "        rel material:binding = </Mat>\n    }\n";
  text += "}\n\ndef Material \"Mat\"\n{\n}\n";
  return text;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  const std::string text = meshLayer(in);
  sdg::usd::ComposedStage composed;
  try {
    sdg::usd::Layer layer = sdg::usd::readUsdaLayer(text, "mesh.usda");
    composed = sdg::usd::composeStage("mesh.usda", [&](const std::string&) { return layer; });
  } catch (const sdg::usd::UsdError& e) {
    // The text is built well formed: a parse error is the harness's bug.
    std::fprintf(stderr, "%s\n%s\n", e.what(), text.c_str());
    __builtin_trap();
  }
  static const sdg::BehaviorCatalog catalog;
  sdg::Stage stage;
  sdg::UsdImportOptions options;
  options.runDefaults = false;
  sdg::UsdImportReport report;
  sdg::Diagnostics diag;
  try {
    importUsdPrims(composed, "/", stage, "/", catalog, options, report, diag);
  } catch (const sdg::SceneError&) {
  }
  // Triangulated whatever the import said, as a cache would: the
  // triangulation checks the arrays itself.
  stage.traverse([](const sdg::Prim& prim) {
    if (prim.type() != sdg::PrimType::Mesh) return;
    if (auto mesh = sdg::inlineMeshOf(prim, 0)) {
      try {
        sdg::MeshData triangles = sdg::triangulateInlineMesh(*mesh, prim.path());
        (void)triangles;
      } catch (const sdg::RunError&) {
      }
    }
  });
  return 0;
}
