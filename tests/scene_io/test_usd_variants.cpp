// USD variant selections chosen on the command line
// (`--set /World/Prop.variants:SET=VARIANT`): applied before composition,
// USD's rule kept where nothing is chosen (no variant without an authored
// selection), and a set, variant or prim the stage lacks reported at the
// --set that named it (tests/data/usd/variants.usda).
#include <catch2/catch.hpp>

#include "scene_io/overrides.h"
#include "scene_io/scene_fixtures.h"
#include "scene_io/usd_import.h"

namespace sdg {
namespace {

const std::string kStage = std::string(SDG_SOURCE_DIR) + "/tests/data/usd/variants.usda";

Scene importWith(const std::vector<std::string>& overrides) {
  UsdImportReport report;
  return importUsdScene(kStage, test::testCatalog(), usdImportOptionsFor(overrides), report);
}

double cubeSize(const Scene& scene) { return scene.stage.find("/World/Prop")->getDouble("size"); }
Vec3f displayColor(const Scene& scene) {
  return scene.stage.find("/World/Prop")->value("primvars:displayColor")->get<Vec3f>();
}

std::string firstProblem(const std::vector<std::string>& overrides) {
  try {
    importWith(overrides);
  } catch (const SceneError& e) {
    return e.problems().front().loc.str() + ": " + e.problems().front().message;
  }
  return "no error";
}

}  // namespace

TEST_CASE("usd variants: the authored selection applies, a set without one applies no variant", "[usd_import][variants]") {
  const Scene scene = importWith({});
  CHECK(displayColor(scene).isApprox(Vec3f(0.1f, 0.2f, 0.9f)));
  CHECK(scene.stage.find("/World/Prop")->findAttribute("size") == nullptr);  // the fallback size
  CHECK(scene.stage.find("/World/Prop/Marker") == nullptr);
}

TEST_CASE("usd variants: --set PRIM.variants:SET=VARIANT chooses, over the authored selection too", "[usd_import][variants]") {
  const Scene big = importWith({"/World/Prop.variants:size=big", "/World/Prop.variants:color=red"});
  CHECK(cubeSize(big) == 3.0);
  CHECK(displayColor(big).isApprox(Vec3f(0.9f, 0.1f, 0.1f)));
  const Scene small = importWith({"/World/Prop.variants:size=small"});
  CHECK(cubeSize(small) == 0.5);
  CHECK(small.stage.find("/World/Prop/Marker") != nullptr);  // a prim the variant defines
  CHECK(displayColor(small).isApprox(Vec3f(0.1f, 0.2f, 0.9f)));
}

TEST_CASE("usd variants: other overrides are left to applyOverrides, which skips the selections", "[usd_import][variants]") {
  const std::vector<std::string> overrides = {"/World/Prop.size=2", "/World/Prop.variants:size=big"};
  Diagnostics diag;
  CHECK(variantSelections(overrides, diag).size() == 1);
  Scene scene = importWith(overrides);
  applyOverrides(overrides, test::testCatalog(), scene, diag);
  CHECK_FALSE(diag.hasErrors());
  CHECK(cubeSize(scene) == 2.0);  // --set of the attribute wins over the variant's opinion
}

TEST_CASE("usd variants: what the stage lacks is an error at the --set", "[usd_import][variants]") {
  CHECK_THAT(firstProblem({"render.resolution=[64,64]", "/World/Prop.variants:size=huge"}),
             Catch::StartsWith("--set[2]:1:1: ") && Catch::Contains("variant set 'size' has no variant 'huge'") &&
                 Catch::Contains("big, small"));
  CHECK_THAT(firstProblem({"/World/Prop.variants:shape=round"}),
             Catch::StartsWith("--set[1]:1:1: ") && Catch::Contains("has no variant set 'shape'"));
  CHECK_THAT(firstProblem({"/World/Nothing.variants:size=big"}),
             Catch::StartsWith("--set[1]:1:1: ") && Catch::Contains("there is no prim /World/Nothing"));
  CHECK_THAT(firstProblem({"/World/Prop.variants:size="}),
             Catch::StartsWith("--set[1]:1:1: ") && Catch::Contains("expected PRIM.variants:SET=VARIANT"));
}

}  // namespace sdg
