// primvars:displayColor and primvars:displayOpacity of every interpolation
// (scene_io/usd_display_primvars.cpp, usd_geometry.cpp): constant ones on
// the gprim, the others per face-vertex on the Mesh, the triangulated
// mesh's vertex colours, the render list's material, export-usd and back.
#include <catch2/catch.hpp>

#include "assets/inline_mesh.h"
#include "assets/mesh_source.h"
#include "render/render_list.h"
#include "scene_io/usd_export.h"
#include "scene_io/usd_fixtures.h"
#include "scene_io/scene_loader.h"
#include "scene_io/scene_validate.h"
#include "scene_io/scene_writer.h"
#include "scene_io/usd_import.h"
#include "usd/usda_writer.h"

using namespace sdg;

namespace {

struct Imported {
  Stage stage;
  Diagnostics diag;
  UsdImportReport report;
};

// Two quads side by side: points 0 1 2 along the bottom, 3 4 5 along the
// top; face 0 is the left quad, face 1 the right.
std::string quadsPrim(const std::string& name, const std::string& primvars, const std::string& children = "") {
  return "def Mesh \"" + name + R"("
{
    int[] faceVertexCounts = [4, 4]
    int[] faceVertexIndices = [0, 1, 4, 3, 1, 2, 5, 4]
    point3f[] points = [(0, 0, 0), (1, 0, 0), (2, 0, 0), (0, 1, 0), (1, 1, 0), (2, 1, 0)]
)" + primvars + children + "}\n";
}

std::string twoQuads(const std::string& primvars, const std::string& children = "") {
  return "#usda 1.0\n" + quadsPrim("Quads", primvars, children);
}

void importText(const std::string& text, Imported& out) {
  const usd::ComposedStage composed = test::composeText(text);
  UsdImportOptions options;
  options.runDefaults = false;
  importUsdPrims(composed, "/", out.stage, "/", test::builtinCatalog(), options, out.report, out.diag);
}

std::vector<float> floats(const Prim& p, const std::string& name) {
  const Value* v = p.value(name);
  REQUIRE(v);
  const auto items = v->get<FloatArray>().items();
  return {items.begin(), items.end()};
}

// Per corner: the left quad's four corners, then the right quad's.
std::vector<float> repeat(std::initializer_list<std::initializer_list<float>> perCorner) {
  std::vector<float> out;
  for (const auto& c : perCorner) out.insert(out.end(), c.begin(), c.end());
  return out;
}

const std::vector<float> kRedGreen = repeat({{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}});

std::string errors(const Diagnostics& diag) {
  std::string out;
  for (const Diagnostic& d : diag.all())
    if (d.severity == Severity::Error) out += d.loc.str() + ": " + d.message + "\n";
  return out;
}

}  // namespace

TEST_CASE("usd display primvars: uniform colours, one per face", "[usd_import][display_primvars]") {
  Imported in;
  importText(twoQuads(R"(    color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0)] (interpolation = "uniform")
)"),
             in);
  REQUIRE(errors(in.diag).empty());
  const Prim& quads = *in.stage.find("/Quads");
  CHECK(quads.value("primvars:displayColor:faceVarying")->type() == ValueType::Color3fArray);
  CHECK(floats(quads, "primvars:displayColor:faceVarying") == kRedGreen);
  // The constant stays unauthored: the per-corner colours replace it.
  CHECK(!quads.findAttribute("primvars:displayColor"));
}

TEST_CASE("usd display primvars: vertex and varying colours follow the points", "[usd_import][display_primvars]") {
  for (const char* interpolation : {"vertex", "varying"}) {
    CAPTURE(interpolation);
    Imported in;
    importText(twoQuads(std::string(R"(    color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0), (0, 1, 1), (1, 0, 1)] (interpolation = ")") +
                        interpolation + "\")\n"),
               in);
    REQUIRE(errors(in.diag).empty());
    // Corners 0 1 4 3 | 1 2 5 4.
    CHECK(floats(*in.stage.find("/Quads"), "primvars:displayColor:faceVarying") ==
          repeat({{1, 0, 0}, {0, 1, 0}, {0, 1, 1}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}}));
  }
}

TEST_CASE("usd display primvars: indexed faceVarying colours", "[usd_import][display_primvars]") {
  Imported in;
  importText(twoQuads(R"(    color3f[] primvars:displayColor = [(0, 1, 0), (1, 0, 0)] (interpolation = "faceVarying")
    int[] primvars:displayColor:indices = [1, 1, 1, 1, 0, 0, 0, 0]
)"),
             in);
  REQUIRE(errors(in.diag).empty());
  CHECK(floats(*in.stage.find("/Quads"), "primvars:displayColor:faceVarying") == kRedGreen);
}

TEST_CASE("usd display primvars: constant ones stay the gprim's attributes", "[usd_import][display_primvars]") {
  Imported in;
  // One item without interpolation, and a constant one of several items
  // through its indices: USD reads the first element.
  importText(twoQuads(R"(    color3f[] primvars:displayColor = [(0.1, 0.2, 0.3), (0.9, 0.9, 0.9)] (interpolation = "constant")
    int[] primvars:displayColor:indices = [0]
    float[] primvars:displayOpacity = [0.25]
)"),
             in);
  REQUIRE(errors(in.diag).empty());
  const Prim& quads = *in.stage.find("/Quads");
  CHECK(quads.value("primvars:displayColor")->get<Vec3f>().isApprox(Vec3f(0.1f, 0.2f, 0.3f)));
  CHECK(quads.getFloat("primvars:displayOpacity") == 0.25f);
  CHECK(!quads.findAttribute("primvars:displayColor:faceVarying"));
  CHECK(!quads.findAttribute("primvars:displayOpacity:faceVarying"));
  // Nothing per vertex: the triangulated mesh has no colours.
  CHECK(meshDataFor(meshKeyOf(quads, 0), AssetResolver{}, "/Quads").colors.empty());
}

TEST_CASE("usd display primvars: an unauthored interpolation is read from the count", "[usd_import][display_primvars]") {
  Imported in;
  importText(twoQuads(R"(    color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0)]
    float[] primvars:displayOpacity = [1, 1, 1, 1, 0, 0, 0, 0]
)"),
             in);
  REQUIRE(errors(in.diag).empty());
  const Prim& quads = *in.stage.find("/Quads");
  CHECK(floats(quads, "primvars:displayColor:faceVarying") == kRedGreen);  // two items: one per face
  CHECK(floats(quads, "primvars:displayOpacity:faceVarying") == std::vector<float>{1, 1, 1, 1, 0, 0, 0, 0});
}

TEST_CASE("usd display primvars: wrong counts and indices are located errors", "[usd_import][display_primvars]") {
  SECTION("a count that fits nothing") {
    Imported in;
    importText(twoQuads("    color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0), (0, 0, 1)]\n"), in);
    const std::string e = errors(in.diag);
    CHECK_THAT(e, Catch::Contains("/v/scene.usda:7:"));
    CHECK_THAT(e, Catch::Contains("/Quads.primvars:displayColor: 3 items and no interpolation; expected one per point (6), "
                                  "face-vertex (8) or face (2)"));
  }
  SECTION("too few for the interpolation") {
    Imported in;
    importText(twoQuads("    color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0)] (interpolation = \"vertex\")\n"), in);
    CHECK_THAT(errors(in.diag), Catch::Contains("/Quads.primvars:displayColor: vertex needs 6 items (one per point), found 2"));
  }
  SECTION("an index outside the values") {
    Imported in;
    importText(twoQuads(R"(    color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0)] (interpolation = "uniform")
    int[] primvars:displayColor:indices = [0, 2]
)"),
               in);
    CHECK_THAT(errors(in.diag), Catch::Contains("primvars:displayColor:indices: expected each index to be one of the 2 values (0 to 1), found 2 at [1]"));
  }
  SECTION("not a colour") {
    Imported in;
    importText(twoQuads("    float[] primvars:displayColor = [1, 0]\n"), in);
    CHECK_THAT(errors(in.diag), Catch::Contains("/Quads.primvars:displayColor: expected color3f[] (lists of 3 numbers r, g, b), found float[]"));
  }
}

TEST_CASE("usd display primvars: a generated gprim keeps the first colour, with a warning",
          "[usd_import][display_primvars]") {
  Imported in;
  importText(R"(#usda 1.0
def Cube "Box"
{
    color3f[] primvars:displayColor = [(0, 0, 1), (1, 0, 0), (1, 0, 0), (1, 0, 0), (1, 0, 0), (1, 0, 0)] (interpolation = "uniform")
}
)",
             in);
  REQUIRE(errors(in.diag).empty());
  CHECK(in.stage.find("/Box")->value("primvars:displayColor")->get<Vec3f>().isApprox(Vec3f(0, 0, 1)));
  bool warned = false;
  for (const Diagnostic& d : in.diag.all())
    warned = warned || (d.severity == Severity::Warning && d.message.find("drawn with the first item") != std::string::npos);
  CHECK(warned);
}

TEST_CASE("usd display primvars: a generated gprim's empty or non-integer indices (found by fuzzing)",
          "[usd_import][display_primvars]") {
  SECTION("an empty index list is no indexing") {
    Imported in;
    importText(R"(#usda 1.0
def Cube "Box"
{
    color3f[] primvars:displayColor = [(0, 0, 1)]
    int[] primvars:displayColor:indices = []
}
)",
               in);
    REQUIRE(errors(in.diag).empty());
    CHECK(in.stage.find("/Box")->value("primvars:displayColor")->get<Vec3f>().isApprox(Vec3f(0, 0, 1)));
  }
  SECTION("indices that are not integers are a located error") {
    Imported in;
    importText(R"(#usda 1.0
def Cube "Box"
{
    color3f[] primvars:displayColor = [(0, 0, 1)]
    string[] primvars:displayColor:indices = ["a"]
}
)",
               in);
    CHECK_THAT(errors(in.diag), Catch::Contains("/v/scene.usda:5:5") &&
                                    Catch::Contains("/Box.primvars:displayColor:indices: expected int[], found string[]"));
  }
}

TEST_CASE("usd display primvars: a GeomSubset keeps its own faces' colours", "[usd_import][display_primvars]") {
  Imported in;
  importText(twoQuads(R"(    color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0)] (interpolation = "uniform")
)",
                      R"(    def GeomSubset "Right"
    {
        uniform token elementType = "face"
        int[] indices = [1]
        rel material:binding = </M>
    }
)") + "def Material \"M\"\n{\n}\n",
             in);
  REQUIRE(errors(in.diag).empty());
  CHECK(floats(*in.stage.find("/Quads"), "primvars:displayColor:faceVarying") == repeat({{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0}}));
  CHECK(floats(*in.stage.find("/Quads/Right"), "primvars:displayColor:faceVarying") ==
        repeat({{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}}));
}

TEST_CASE("usd display primvars: the triangulated mesh carries colour and opacity per vertex",
          "[usd_import][display_primvars]") {
  Imported in;
  importText(twoQuads(R"(    color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0)] (interpolation = "uniform")
    float[] primvars:displayOpacity = [0.75, 0.25] (interpolation = "uniform")
)"),
             in);
  REQUIRE(errors(in.diag).empty());
  const Prim& quads = *in.stage.find("/Quads");
  const MeshData mesh = meshDataFor(meshKeyOf(quads, 0), AssetResolver{}, "/Quads");
  REQUIRE(mesh.colors.size() == mesh.positions.size());
  REQUIRE(mesh.colors.size() == 8);  // one vertex per corner
  for (size_t i = 0; i < 8; ++i) {
    CAPTURE(i);
    CHECK(mesh.colors[i].isApprox(i < 4 ? Eigen::Vector4f(1, 0, 0, 0.75f) : Eigen::Vector4f(0, 1, 0, 0.25f)));
  }
  // A colour array of the wrong length is the mesh's problem, named.
  auto broken = std::make_shared<InlineMesh>(*inlineMeshOf(quads, 0));
  broken->displayColor = Value::makeFloatArray(ValueType::Color3fArray, {1, 0, 0});
  CHECK(inlineMeshProblem(*broken) == "primvars:displayColor:faceVarying has 1 items; expected one per face-vertex (8)");
}

TEST_CASE("usd display primvars: the render list uses them only without a bound material",
          "[usd_import][display_primvars]") {
  Imported in;
  importText(twoQuads(R"(    color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0)] (interpolation = "uniform")
    float[] primvars:displayOpacity = [1, 0] (interpolation = "uniform")
)") + quadsPrim("Faded", "    float[] primvars:displayOpacity = [0.3]\n") +
                 R"(def Material "M"
{
    token outputs:surface.connect = </M/S.outputs:surface>
    def Shader "S"
    {
        uniform token info:id = "UsdPreviewSurface"
        token outputs:surface
    }
}
def Mesh "Bound" (
    prepend apiSchemas = ["MaterialBindingAPI"]
)
{
    int[] faceVertexCounts = [3]
    int[] faceVertexIndices = [0, 1, 2]
    point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
    color3f[] primvars:displayColor = [(1, 0, 0), (0, 1, 0), (0, 0, 1)] (interpolation = "vertex")
    rel material:binding = </M>
}
)",
             in);
  REQUIRE(errors(in.diag).empty());
  const RenderList list = buildRenderList(in.stage);
  auto item = [&](const std::string& path) -> const RenderItem& {
    for (const RenderItem& i : list.items)
      if (i.primPath == path) return i;
    FAIL("no render item " << path);
    return list.items[0];
  };
  const RenderMaterial& quads = item("/Quads").material;
  CHECK(quads.vertexColors);
  CHECK(quads.baseColor == Vec3f(1, 1, 1));  // the vertex colour replaces displayColor
  CHECK(quads.opacity == OpacitySource::Constant);
  CHECK(quads.opacityConstant == 1.0f);
  CHECK(quads.opacityCutoff == 0.5f);
  const RenderMaterial& faded = item("/Faded").material;  // a constant displayOpacity: a cut-out at one half
  CHECK(!faded.vertexColors);
  CHECK(faded.opacity == OpacitySource::Constant);
  CHECK(faded.opacityConstant == Approx(0.3f));
  const RenderMaterial& bound = item("/Bound").material;  // a bound material wins
  CHECK(bound.fromPrim);
  CHECK(!bound.vertexColors);
  CHECK(!bound.cutOut());
}

TEST_CASE("usd display primvars: export-usd writes them back as USD's faceVarying primvars",
          "[usd_import][usd_export][display_primvars]") {
  Imported in;
  importText(twoQuads(R"(    color3f[] primvars:displayColor = [(0, 1, 0), (1, 0, 0)] (interpolation = "faceVarying")
    int[] primvars:displayColor:indices = [1, 1, 1, 1, 0, 0, 0, 0]
    float[] primvars:displayOpacity = [1, 0.5] (interpolation = "uniform")
)") + R"(def Cube "Box"
{
    float[] primvars:displayOpacity = [0.75]
}
)",
             in);
  REQUIRE(errors(in.diag).empty());
  Scene scene;
  scene.stage = std::move(in.stage);
  usd::Layer layer = exportUsdLayer(scene, AssetResolver{}, UsdExportOptions{});
  layer.identifier = "/v/scene.usda";
  const std::string text = usd::writeUsdaLayer(layer);
  CHECK_THAT(text, Catch::Contains("color3f[] primvars:displayColor = [(1, 0, 0), (1, 0, 0), (1, 0, 0), (1, 0, 0), (0, 1, 0)"));
  CHECK_THAT(text, Catch::Contains("interpolation = \"faceVarying\""));
  CHECK_THAT(text, Catch::Contains("float[] primvars:displayOpacity = [0.75]"));
  CHECK_THAT(text, !Catch::Contains("displayColor:faceVarying"));
  Imported back;
  importText(text, back);
  REQUIRE(errors(back.diag).empty());
  const Prim& quads = *back.stage.find("/Quads");
  CHECK(floats(quads, "primvars:displayColor:faceVarying") == kRedGreen);
  CHECK(floats(quads, "primvars:displayOpacity:faceVarying") == std::vector<float>{1, 1, 1, 1, 0.5f, 0.5f, 0.5f, 0.5f});
  CHECK(!quads.findAttribute("primvars:displayColor"));
  CHECK(back.stage.find("/Box")->getFloat("primvars:displayOpacity") == 0.75f);
}

TEST_CASE("usd display primvars: the YAML form reads, validates and writes back", "[scene_io][display_primvars]") {
  const std::string yaml = R"(version: 1
prims:
  /Quads:
    type: Mesh
    points: [[-2, -1, 0], [0, -1, 0], [2, -1, 0], [-2, 1, 0], [0, 1, 0], [2, 1, 0]]
    faceVertexCounts: [4, 4]
    faceVertexIndices: [0, 1, 4, 3, 1, 2, 5, 4]
    primvars:displayColor:faceVarying: [[1, 0, 0], [1, 0, 0], [1, 0, 0], [1, 0, 0],
                                        [0, 1, 0], [0, 1, 0], [0, 1, 0], [0, 1, 0]]
    primvars:displayOpacity:faceVarying: [1, 1, 1, 1, 1, 0, 0, 1]
)";
  const BehaviorCatalog& catalog = test::builtinCatalog();
  const Scene scene = buildScene(sceneDocumentFromText(yaml, "t.yaml"), catalog);
  const Prim& quads = *scene.stage.find("/Quads");
  CHECK(floats(quads, "primvars:displayColor:faceVarying") == kRedGreen);
  CHECK(inlineMeshProblem(*inlineMeshOf(quads, 0)).empty());
  const std::string written = writeSceneYaml(scene, catalog);
  CHECK_THAT(written, Catch::Contains("primvars:displayColor:faceVarying: [[1.0, 0.0, 0.0], [1.0, 0.0, 0.0]"));
  const Scene back = buildScene(sceneDocumentFromText(written, "back.yaml"), catalog);
  CHECK(floats(*back.stage.find("/Quads"), "primvars:displayColor:faceVarying") == kRedGreen);
  CHECK(floats(*back.stage.find("/Quads"), "primvars:displayOpacity:faceVarying") == std::vector<float>{1, 1, 1, 1, 1, 0, 0, 1});
}

TEST_CASE("usd display primvars: a YAML list of the wrong length is a located error", "[scene_io][display_primvars]") {
  const std::string yaml = R"(version: 1
prims:
  /Quad:
    type: Mesh
    points: [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
    faceVertexCounts: [4]
    faceVertexIndices: [0, 1, 2, 3]
    primvars:displayColor:faceVarying: [[1, 0, 0]]
)";
  // Located at the attribute's value (line 8, column 40).
  CHECK_THROWS_WITH(buildScene(sceneDocumentFromText(yaml, "t.yaml"), test::builtinCatalog()),
                    Catch::Contains("t.yaml:8:40:") &&
                        Catch::Contains("/Quad: primvars:displayColor:faceVarying has 1 items; expected one per "
                                        "face-vertex (4)"));
}
