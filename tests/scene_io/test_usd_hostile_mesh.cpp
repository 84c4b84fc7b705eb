// Hostile USD meshes (scene_io/usd_mesh_topology.h): every check of the
// topology and primvars, each a located error naming the prim path and
// attribute with what was expected and what was found, said once (not
// again for each GeomSubset); the files of tests/data/usd/hostile through
// the whole import (a negative face count used to crash it); and the YAML
// inline mesh's own checks (assets/inline_mesh.h).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "assets/inline_mesh.h"
#include "scene_io/scene_fixtures.h"
#include "scene_io/usd_fixtures.h"
#include "scene_io/usd_import.h"
#include "scene_io/usd_mesh_topology.h"

namespace sdg {
namespace {

const std::string kHostile = std::string(SDG_SOURCE_DIR) + "/tests/data/usd/hostile/";

// A quad and a triangle over five points, plus `extra` lines.
std::string meshLayer(const std::string& counts, const std::string& indices, const std::string& extra = "",
                      const std::string& points = "(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0), (0, 0, 1)") {
  return "#usda 1.0\n"
         "def Mesh \"M\"\n"
         "{\n"
         "    point3f[] points = [" + points + "]\n"                 // line 4
         "    int[] faceVertexCounts = [" + counts + "]\n"           // line 5
         "    int[] faceVertexIndices = [" + indices + "]\n" +       // line 6
         extra + "}\n";                                              // extra from line 7
}

const std::string kCounts = "4, 3", kIndices = "0, 1, 2, 3, 0, 1, 4";

// The formatted errors of checking /M of `layer`; `ok` receives the checker's answer.
std::vector<std::string> problems(const std::string& layer, bool* ok = nullptr) {
  usd::ComposedStage stage = test::composeText(layer);
  Diagnostics diag;
  const bool usable = usd_map::checkMeshTopology(*stage.prim("/M"), diag);
  if (ok) *ok = usable;
  std::vector<std::string> out;
  for (const Diagnostic& d : diag.all()) out.push_back(d.format());
  CHECK(usable == out.empty());
  return out;
}

std::string onlyProblem(const std::string& layer) {
  std::vector<std::string> p = problems(layer);
  REQUIRE(p.size() == 1);
  return p[0];
}

// Every message of importing the stage file (SceneError), "" when it imports.
std::string importErrors(const std::string& path) {
  UsdImportReport report;
  try {
    importUsdScene(path, test::testCatalog(), UsdImportOptions{}, report);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("usd hostile mesh: sound meshes pass", "[usd_import][hostile]") {
  CHECK(problems(meshLayer(kCounts, kIndices)).empty());
  CHECK(problems(meshLayer("", "")).empty());  // no faces: nothing to draw, nothing wrong
  // Primvars of every interpolation, indexed or not, at their sizes.
  CHECK(problems(meshLayer(kCounts, kIndices,
                           "    normal3f[] normals = [(0,0,1),(0,0,1),(0,0,1),(0,0,1),(0,0,1)] (interpolation = \"varying\")\n"
                           "    texCoord2f[] primvars:st = [(0,0),(1,0)] (interpolation = \"faceVarying\")\n"
                           "    int[] primvars:st:indices = [0,1,0,1,0,1,0]\n"
                           "    color3f[] primvars:displayColor = [(1,0,0),(0,1,0)] (interpolation = \"uniform\")\n"
                           "    float[] primvars:displayOpacity = [0.5]\n"))
            .empty());
  // A point no face uses may be anything finite; a primvar nothing reads is not checked.
  CHECK(problems(meshLayer(kCounts, kIndices, "    float3[] primvars:velocity = [(1,2,3)] (interpolation = \"vertex\")\n"))
            .empty());
}

TEST_CASE("usd hostile mesh: face counts", "[usd_import][hostile]") {
  CHECK(onlyProblem(meshLayer("4, -1", "0, 1, 2, 3")) ==
        "/v/scene.usda:5:5: error: /M.faceVertexCounts: expected each face to have at least 3 vertices, found -1 "
        "for face 1");
  CHECK_THAT(onlyProblem(meshLayer("4, 2", "0, 1, 2, 3, 0, 4")), Catch::Contains("found 2 for face 1"));
  CHECK_THAT(onlyProblem(meshLayer("0, 4", "0, 1, 2, 3")), Catch::Contains("found 0 for face 0"));
  CHECK_THAT(onlyProblem(meshLayer("-2147483648, -1, 3", "0, 1, 2")),
             Catch::Contains("found -2147483648 for face 0 (2 of 3 counts are)"));
}

TEST_CASE("usd hostile mesh: indices add up to the counts and name points", "[usd_import][hostile]") {
  CHECK(onlyProblem(meshLayer("4, 4", "0, 1, 2, 3")) ==
        "/v/scene.usda:6:5: error: /M.faceVertexIndices: expected 8 indices (the sum of faceVertexCounts), found 4");
  CHECK(onlyProblem(meshLayer("3", "0, 1, 2, 3")) ==
        "/v/scene.usda:6:5: error: /M.faceVertexIndices: expected 3 indices (the sum of faceVertexCounts), found 4");
  CHECK(onlyProblem(meshLayer(kCounts, "0, 1, 2, 3, 0, 7, -1")) ==
        "/v/scene.usda:6:5: error: /M.faceVertexIndices: expected each index to be one of the 5 points (0 to 4), "
        "found 7 at [5] (2 of 7 indices are)");
  // Counts absent, indices present: they add up to nothing.
  CHECK_THAT(onlyProblem("#usda 1.0\ndef Mesh \"M\"\n{\n    point3f[] points = [(0,0,0)]\n"
                         "    int[] faceVertexIndices = [0, 0, 0]\n}\n"),
             Catch::Contains("expected 0 indices (the sum of faceVertexCounts), found 3"));
  // Wrong types a file may hold reach the check as numbers: not whole, or past int32.
  CHECK_THAT(onlyProblem("#usda 1.0\ndef Mesh \"M\"\n{\n    point3f[] points = [(0,0,0),(1,0,0),(0,1,0)]\n"
                         "    double[] faceVertexCounts = [3.5]\n    int[] faceVertexIndices = [0, 1, 2]\n}\n"),
             Catch::Contains("found 3.5 for face 0"));
  CHECK_THAT(onlyProblem("#usda 1.0\ndef Mesh \"M\"\n{\n    point3f[] points = [(0,0,0),(1,0,0),(0,1,0)]\n"
                         "    int[] faceVertexCounts = [3]\n    int64[] faceVertexIndices = [0, 1, 4294967296]\n}\n"),
             Catch::Contains("found 4294967296 at [2]"));
}

TEST_CASE("usd hostile mesh: points are finite", "[usd_import][hostile]") {
  CHECK(onlyProblem(meshLayer("3", "0, 1, 2", "", "(0, 0, 0), (1, nan, 0), (0, 1, 0)")) ==
        "/v/scene.usda:4:5: error: /M.points: expected finite coordinates, found (1, nan, 0) at [1]");
  CHECK_THAT(onlyProblem(meshLayer("3", "0, 1, 2", "", "(0, 0, -inf), (1, 0, 0), (0, 1e39, 0)")),
             Catch::Contains("found (0, 0, -inf) at [0] (2 of 3 points are)"));
  // Points and topology are told apart: both reported.
  CHECK(problems(meshLayer("3", "0, 1, 5", "", "(0, 0, 0), (1, nan, 0), (0, 1, 0)")).size() == 2);
}

TEST_CASE("usd hostile mesh: primvar sizes for every interpolation", "[usd_import][hostile]") {
  auto primvar = [](const std::string& decl, const std::string& interpolation, const std::string& values) {
    return meshLayer(kCounts, kIndices,
                     "    " + decl + " = [" + values + "]" +
                         (interpolation.empty() ? "" : " (interpolation = \"" + interpolation + "\")") + "\n");
  };
  // 2 faces, 5 points, 7 face-vertices.
  CHECK(onlyProblem(primvar("normal3f[] normals", "vertex", "(0,0,1),(0,0,1),(0,0,1)")) ==
        "/v/scene.usda:7:5: error: /M.normals: vertex needs 5 items (one per point), found 3");
  CHECK_THAT(onlyProblem(primvar("normal3f[] normals", "", "(0,0,1)")),
             Catch::Contains("/M.normals: vertex needs 5 items"));  // normals are per vertex unless said
  CHECK_THAT(onlyProblem(primvar("normal3f[] primvars:normals", "faceVarying", "(0,0,1),(0,0,1)")),
             Catch::Contains("/M.primvars:normals: faceVarying needs 7 items (one per face-vertex), found 2"));
  CHECK_THAT(onlyProblem(primvar("texCoord2f[] primvars:st", "varying", "(0,0)")),
             Catch::Contains("/M.primvars:st: varying needs 5 items (one per point), found 1"));
  CHECK_THAT(onlyProblem(primvar("texCoord2f[] primvars:UVMap", "faceVarying", "(0,0)")),
             Catch::Contains("/M.primvars:UVMap: faceVarying needs 7 items"));
  CHECK_THAT(onlyProblem(primvar("color3f[] primvars:displayColor", "uniform", "(1,0,0)")),
             Catch::Contains("/M.primvars:displayColor: uniform needs 2 items (one per face), found 1"));
  CHECK_THAT(onlyProblem(primvar("float[] primvars:displayOpacity", "vertex", "1, 1")),
             Catch::Contains("/M.primvars:displayOpacity: vertex needs 5 items (one per point), found 2"));
  CHECK_THAT(onlyProblem(primvar("float[] primvars:displayOpacity", "perFace", "1")),
             Catch::Contains("/M.primvars:displayOpacity: expected interpolation constant, uniform, vertex, varying "
                             "or faceVarying, found 'perFace'"));
  // More than needed is what USD writers sometimes leave: accepted.
  CHECK(problems(primvar("color3f[] primvars:displayColor", "uniform", "(1,0,0),(0,1,0),(0,0,1)")).empty());
}

TEST_CASE("usd hostile mesh: indexed primvars", "[usd_import][hostile]") {
  const std::string st = "    texCoord2f[] primvars:st = [(0,0),(1,0),(1,1)] (interpolation = \"faceVarying\")\n";
  CHECK(onlyProblem(meshLayer(kCounts, kIndices, st + "    int[] primvars:st:indices = [0, 1, 2, 3, 0, -1, 0]\n")) ==
        "/v/scene.usda:8:5: error: /M.primvars:st:indices: expected each index to be one of the 3 values (0 to 2), "
        "found 3 at [3] (2 of 7 indices are)");
  CHECK_THAT(onlyProblem(meshLayer(kCounts, kIndices, st + "    int[] primvars:st:indices = [0, 1]\n")),
             Catch::Contains("/v/scene.usda:8:5: error: /M.primvars:st:indices: faceVarying needs 7 indices "
                             "(one per face-vertex), found 2"));
  // An index into an empty value list.
  CHECK_THAT(onlyProblem(meshLayer(kCounts, kIndices,
                                   "    color3f[] primvars:displayColor = [(1,0,0)] (interpolation = \"uniform\")\n"
                                   "    int[] primvars:displayColor:indices = [0, 1]\n")),
             Catch::Contains("/M.primvars:displayColor:indices: expected each index to be one of the 1 values (0 to 0), "
                             "found 1 at [1]"));
}

TEST_CASE("usd hostile mesh: GeomSubset faces, and each mesh problem said once", "[usd_import][hostile]") {
  usd::ComposedStage stage = test::composeText(
      "#usda 1.0\ndef Mesh \"M\"\n{\n    def GeomSubset \"S\"\n    {\n        int[] indices = [1, 2, -1]\n    }\n}\n");
  Diagnostics diag;
  CHECK_FALSE(usd_map::subsetFaces(*stage.prim("/M/S"), "/M", 2, diag));
  REQUIRE(diag.all().size() == 1);
  CHECK(diag.all()[0].format() ==
        "/v/scene.usda:6:9: error: /M/S.indices: expected faces of /M (0 to 1), found 2 at [1] (2 of 3 indices are)");
  Diagnostics fine;
  CHECK(usd_map::subsetFaces(*test::composeText("#usda 1.0\ndef GeomSubset \"S\"\n{\n    int[] indices = [2, 0]\n}\n")
                                  .prim("/S"),
                             "/M", 3, fine) == std::vector<int32_t>{2, 0});
  CHECK_FALSE(fine.hasErrors());

  // A mesh with two material subsets and a negative count: one error, not three.
  const std::string subsets =
      "    def GeomSubset \"A\"\n    {\n        uniform token elementType = \"face\"\n        int[] indices = [0]\n"
      "        rel material:binding = </Mat>\n    }\n"
      "    def GeomSubset \"B\"\n    {\n        uniform token elementType = \"face\"\n        int[] indices = [1]\n"
      "        rel material:binding = </Mat>\n    }\n";
  usd::ComposedStage bad = test::composeText(meshLayer("4, -3", kIndices, subsets) + "def Material \"Mat\"\n{\n}\n");
  Stage out;
  UsdImportReport report;
  Diagnostics importDiag;
  UsdImportOptions options;
  options.runDefaults = false;
  importUsdPrims(bad, "/", out, "/", test::builtinCatalog(), options, report, importDiag);
  REQUIRE(importDiag.errorCount() == 1);
  CHECK_THAT(importDiag.all()[0].format(), Catch::Contains("/M.faceVertexCounts: expected each face"));
}

TEST_CASE("usd hostile mesh: the hostile files fail the import, located, once", "[usd_import][hostile]") {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"negative_count.usda", "negative_count.usda:13:9: error: /World/Bad.faceVertexCounts: expected each face to have at "
                              "least 3 vertices, found -1 for face 1"},
      {"two_vertex_face.usda", "two_vertex_face.usda:13:9: error: /World/Bad.faceVertexCounts: expected each face to have "
                               "at least 3 vertices, found 2 for face 1"},
      {"counts_sum.usda", "counts_sum.usda:14:9: error: /World/Bad.faceVertexIndices: expected 8 indices"},
      {"index_outside.usda", "index_outside.usda:14:9: error: /World/Bad.faceVertexIndices: expected each index to be one "
                             "of the 5 points (0 to 4), found 7 at [5]"},
      {"nan_points.usda", "nan_points.usda:12:9: error: /World/Bad.points: expected finite coordinates, found (1, nan, 0) at [2]"},
      {"inf_points.usda", "inf_points.usda:12:9: error: /World/Bad.points: expected finite coordinates"},
      {"normals_short.usda", "normals_short.usda:15:9: error: /World/Bad.normals: vertex needs 5 items (one per point), found 3"},
      {"st_facevarying_short.usda", "st_facevarying_short.usda:15:9: error: /World/Bad.primvars:st: faceVarying needs 7 items"},
      {"st_indices_outside.usda", "st_indices_outside.usda:18:9: error: /World/Bad.primvars:st:indices: expected each index "
                                  "to be one of the 4 values (0 to 3), found 9 at [2]"},
      {"display_color_uniform_short.usda", "display_color_uniform_short.usda:15:9: error: /World/Bad.primvars:displayColor: "
                                           "uniform needs 2 items (one per face), found 1"},
      {"display_opacity_bad_interpolation.usda", "/World/Bad.primvars:displayOpacity: expected interpolation"},
      {"subset_outside.usda", "subset_outside.usda:20:13: error: /World/Bad/Top.indices: expected faces of /World/Bad (0 to "
                              "1), found 5 at [1]"},
  };
  for (const auto& [file, message] : cases) {
    INFO(file);
    const std::string errors = importErrors(kHostile + file);
    CHECK_THAT(errors, Catch::Contains(message));
    CHECK(std::count(errors.begin(), errors.end(), '\n') == 0);  // said once
  }
}

TEST_CASE("usd hostile mesh: the YAML inline mesh refuses what the USD import refuses", "[usd_import][hostile]") {
  const std::string head =
      "version: 1\nprims:\n  /M:\n    type: Mesh\n    points: [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n";
  CHECK_THAT(test::errorsOf(head + "    faceVertexCounts: [3, 2]\n    faceVertexIndices: [0, 1, 2, 0, 1]\n"),
             Catch::Contains("t.yaml:6:") &&
                 Catch::Contains("/M: faceVertexCounts: expected each face to have at least 3 vertices, found 2 for face 1"));
  CHECK_THAT(test::errorsOf(head + "    faceVertexCounts: [3, -1]\n    faceVertexIndices: [0, 1, 2]\n"),
             Catch::Contains("found -1 for face 1"));
  CHECK_THAT(test::errorsOf(head + "    faceVertexCounts: [3]\n    faceVertexIndices: [0, 1, 5]\n"),
             Catch::Contains("t.yaml:7:") && Catch::Contains("faceVertexIndices[2] is 5, outside the 3 points"));
  CHECK(test::errorsOf(head + "    faceVertexCounts: [3]\n    faceVertexIndices: [0, 1, 2]\n").empty());

  // Non-finite points never come from YAML (the reader refuses them); a
  // stage built otherwise is caught before triangulation.
  Stage stage;
  Prim& prim = stage.definePrim("/M", PrimType::Mesh);
  prim.setAttribute("points", Value::makeFloatArray(ValueType::Point3fArray, {0, 0, 0, 1, 0, 0, 0, NAN, 0}));
  prim.setAttribute("faceVertexCounts", Value::makeIntArray({3}));
  prim.setAttribute("faceVertexIndices", Value::makeIntArray({0, 1, 2}));
  std::string attribute;
  CHECK(inlineMeshProblem(*inlineMeshOf(prim, 0), &attribute) == "points[2] is not finite (found nan)");
  CHECK(attribute == "points");
  CHECK_THROWS_AS(triangulateInlineMesh(*inlineMeshOf(prim, 0), "/M"), RunError);
}

}  // namespace sdg
