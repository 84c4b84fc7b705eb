// Subdivision surfaces through scenes: render.subdivision_level reaches the
// geometry every reader draws (default 2, none = as authored, --set), the
// tags are written in YAML, read from USD (an unauthored subdivisionScheme is
// USD's catmullClark) and written back by export-usd.
#include <catch2/catch.hpp>

#include "assets/mesh_source.h"
#include "render/render_list.h"
#include "run/scene_setup.h"
#include "scene_io/usd_export.h"
#include "usd/compose.h"
#include "usd/layer_io.h"
#include "usd/usda_writer.h"

namespace sdg {
namespace {

const std::string kCubeScene = R"(version: 1
prims:
  /World: {type: Xform}
  /World/Ball:
    type: Mesh
    points: [[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1], [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]]
    faceVertexCounts: [4, 4, 4, 4, 4, 4]
    faceVertexIndices: [0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7]
)";

LoadedScene loadText(const std::string& text, std::vector<std::string> overrides = {}) {
  return loadSceneForRun(SceneRequest{.scenePath = "cube.yaml", .overrides = std::move(overrides), .sceneText = text});
}

// Triangles of a prim as the renderers get it (the render list's key).
MeshData drawn(const LoadedScene& loaded, const std::string& path) {
  const RenderList list = buildRenderList(loaded.scene.stage);
  for (const RenderItem& item : list.items)
    if (item.primPath == path) return meshDataFor(item.mesh, loaded.assets, path);
  FAIL("no render item " << path);
  return {};
}

}  // namespace

TEST_CASE("subdivision scenes: render.subdivision_level refines what is drawn, none keeps the cage", "[subdivision]") {
  // A Mesh without subdivisionScheme is catmullClark (the stage's fallback, USD's).
  const LoadedScene byDefault = loadText(kCubeScene);
  CHECK(byDefault.scene.render.getString("subdivision_level") == "2");
  CHECK(byDefault.scene.stage.metadata().subdivisionLevel == 2);
  CHECK(drawn(byDefault, "/World/Ball").triangleCount() == 192);
  CHECK(drawn(loadText(kCubeScene, {"render.subdivision_level=1"}), "/World/Ball").triangleCount() == 48);
  const LoadedScene cage = loadText(kCubeScene, {"render.subdivision_level=none"});
  CHECK(cage.scene.stage.metadata().subdivisionLevel == 0);
  CHECK(drawn(cage, "/World/Ball").triangleCount() == 12);
  // The level is part of the cache key: one process can hold both.
  CHECK(buildRenderList(cage.scene.stage).items[0].meshId != buildRenderList(byDefault.scene.stage).items[0].meshId);
  // In the file, and subdivisionScheme none on the prim.
  CHECK(drawn(loadText(kCubeScene + "render: {subdivision_level: 3}\n"), "/World/Ball").triangleCount() == 768);
  CHECK(drawn(loadText(kCubeScene + "    subdivisionScheme: none\n"), "/World/Ball").triangleCount() == 12);
  // A level outside the table is refused where it is written.
  CHECK_THROWS_WITH(loadText(kCubeScene, {"render.subdivision_level=9"}),
                    Catch::Contains("expected one of none, 1, 2, 3, 4, 5, 6"));
}

TEST_CASE("subdivision scenes: creases, corners and holes are written in YAML and checked", "[subdivision]") {
  const std::string tagged = kCubeScene + R"(    creaseIndices: [4, 5, 6, 7, 4]
    creaseLengths: [5]
    creaseSharpnesses: [10]
    cornerIndices: [4, 5, 6, 7]
    cornerSharpnesses: [10, 10, 10, 10]
    holeIndices: [0]
    interpolateBoundary: edgeOnly
)";
  const MeshData mesh = drawn(loadText(tagged), "/World/Ball");
  CHECK(mesh.triangleCount() == 160);  // 5 faces x 16 quads x 2
  CHECK(mesh.bounds.max().z() == Approx(1.0f));  // the creased top stays at the cage's top
  CHECK(mesh.bounds.min().z() > -0.99f);  // the smooth bottom is rounded off
  // A crease that does not fit its indices: exit 2 material, naming the prim.
  CHECK_THROWS_WITH(loadText(kCubeScene + "    creaseIndices: [4, 5]\n    creaseLengths: [3]\n"),
                    Catch::Contains("/World/Ball: creaseLengths add up to 3 but creaseIndices has 2 items"));
}

TEST_CASE("subdivision scenes: USD tags are imported, drawn, and written back by export-usd", "[subdivision]") {
  const std::string file = std::string(SDG_SOURCE_DIR) + "/tests/data/usd/subdivision.usda";
  const LoadedScene loaded = loadSceneForRun(SceneRequest{.scenePath = file});
  const Stage& stage = loaded.scene.stage;
  const Prim& tagged = *stage.find("/World/Tagged");
  CHECK(tagged.value("creaseIndices")->get<IntArray>().size() == 5);
  CHECK(tagged.value("cornerSharpnesses")->get<FloatArray>().size() == 4);
  CHECK(tagged.getString("interpolateBoundary") == "edgeOnly");
  CHECK(tagged.getString("faceVaryingLinearInterpolation") == "boundaries");
  CHECK(tagged.getString("triangleSubdivisionRule") == "smooth");
  CHECK(stage.find("/World/Smooth")->getString("subdivisionScheme") == "catmullClark");  // USD's fallback
  CHECK(drawn(loaded, "/World/Smooth").triangleCount() == 192);
  CHECK(drawn(loaded, "/World/Tagged").triangleCount() == 160);
  CHECK(drawn(loaded, "/World/Cage").triangleCount() == 12);

  UsdExportOptions options;
  options.catalog = &loaded.registry.catalog();
  usd::Layer layer = exportUsdLayer(loaded.scene, loaded.assets, options);
  layer.identifier = "stage.usda";
  const std::string text = usd::writeUsdaLayer(layer);
  CHECK_THAT(text, Catch::Contains("int[] creaseIndices = [4, 5, 6, 7, 4]"));
  CHECK_THAT(text, Catch::Contains("float[] cornerSharpnesses = [10, 10, 10, 10]"));
  CHECK_THAT(text, Catch::Contains("int[] holeIndices = [0]"));
  CHECK_THAT(text, Catch::Contains("uniform token interpolateBoundary = \"edgeOnly\""));
  const usd::ComposedStage composed =
      usd::composeStage("stage.usda", [text](const std::string& id) { return usd::readUsdaLayer(text, id); });
  const usd::ComposedPrim* prim = composed.prim("/World/Tagged");
  REQUIRE(prim);
  REQUIRE(prim->property("creaseLengths"));
  CHECK(prim->property("creaseLengths")->value.numbers == std::vector<double>{5});
  CHECK(prim->property("creaseSharpnesses")->value.numbers == std::vector<double>{10});
}

}  // namespace sdg
