// A USD stage's own animation: time samples imported as the stage's
// animation table (scene_io/usd_animation.h) and played by the runtime's
// timeline (behavior/animation_playback.h): sampled values at each update,
// held discrete values, layer offsets, behaviors on top, restore on stop,
// and the same values whatever update a run starts counting from.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "behavior/registry.h"
#include "behavior/runtime.h"
#include "scene_io/scene_fixtures.h"
#include "scene_io/usd_import.h"

namespace sdg {
namespace {

const std::string kDir = std::string(SDG_SOURCE_DIR) + "/tests/data/usd/";

Scene importFile(const std::string& path) {
  UsdImportReport report;
  return importUsdScene(path, test::testCatalog(), UsdImportOptions{}, report);
}

Vec3d translate(const Stage& stage, const std::string& path) {
  for (const XformOp& op : stage.find(path)->xformOps())
    if (op.attributeName() == "xformOp:translate") return op.value.get<Vec3d>();
  FAIL("no translate on " << path);
  return {};
}

// Writes the prim's translate to (9, 9, 9) on even updates; puts back what
// it found at play on stop (as the built-in randomizers do).
class PinOnEvenUpdates : public Behavior {
 public:
  void onPlay() override { saved_ = prim().findXformOp("xformOp:translate")->value; }
  void onUpdate(double, double) override {
    if (++updates_ % 2 == 0) prim().findXformOp("xformOp:translate")->value = Value::makeDouble3(Vec3d(9, 9, 9));
  }
  void onStop() override { prim().findXformOp("xformOp:translate")->value = saved_; }

 private:
  Value saved_;
  int updates_ = 0;
};

BehaviorRegistry registryWithPin() {
  BehaviorRegistry registry;
  BehaviorSpec spec;
  spec.name = "pinOnEvenUpdates";
  registry.add(spec, [] { return std::make_unique<PinOnEvenUpdates>(); }, "test");
  return registry;
}

}  // namespace

TEST_CASE("usd animation: time samples become the stage's animation table", "[usd_import]") {
  Scene scene = importFile(kDir + "animated.usda");
  const StageAnimation& anim = scene.stage.animation();
  CHECK(scene.stage.metadata().timeCodesPerSecond == 4);
  const AnimatedValue* t = anim.find("/World/Box", "xformOp:translate");
  REQUIRE(t);
  CHECK(t->xformOp);
  // A prim is sampled at the union of its properties' sample times.
  CHECK(t->times == std::vector<double>{0, 4, 6, 8});
  REQUIRE(anim.find("/World/Box", "visibility"));
  CHECK(anim.find("/World/Box", "visibility")->times == std::vector<double>{0, 4, 6, 8});
  CHECK(anim.find("/World/Box", "visibility")->at(5).get<std::string>() == "invisible");
  REQUIRE(anim.find("/World/Flag", "points"));
  REQUIRE(anim.find("/World/Sun", "inputs:intensity"));
  // Only what changes: the box's size, the flag's topology, the camera are not animated.
  CHECK(anim.size() == 4);
  // Before play the stage shows the start time code.
  CHECK(translate(scene.stage, "/World/Box").isApprox(Vec3d(-1.6, 0, 0.5)));
}

TEST_CASE("usd animation: each update shows startTimeCode + t * timeCodesPerSecond", "[usd_import]") {
  Scene scene = importFile(kDir + "animated.usda");
  const Stage beforePlay = scene.stage;
  BehaviorRegistry registry;
  BehaviorRuntime runtime(scene.stage, registry, BehaviorContext{});
  runtime.init();
  runtime.play();
  for (int step = 1; step <= 10; ++step) {
    runtime.update();
    INFO("update " << step);
    const double tc = std::min(step, 8);  // held after the last sample
    CHECK(translate(scene.stage, "/World/Box").isApprox(Vec3d(-1.6 + 0.4 * tc, 0, 0.5)));
    // Tokens are held: invisible from time code 4 up to (not including) 6.
    const bool invisible = step == 4 || step == 5;
    CHECK(scene.stage.find("/World/Box")->getString("visibility") == (invisible ? "invisible" : "inherited"));
    CHECK(scene.stage.find("/World/Sun")->getFloat("inputs:intensity") == Approx(500 + 250 * tc));
    const FloatArray& points = scene.stage.find("/World/Flag")->value("points")->get<FloatArray>();
    CHECK(points[2] == Approx(1.5 + 0.125 * tc));
  }
  runtime.stop();
  CHECK(scene.stage == beforePlay);
  // Played again from the start: the same values, never accumulated.
  runtime.play();
  runtime.update();
  CHECK(translate(scene.stage, "/World/Box").isApprox(Vec3d(-1.2, 0, 0.5)));
  runtime.stop();
  CHECK(scene.stage == beforePlay);
}

TEST_CASE("usd animation: a behavior writes on top of the samples for the updates it writes", "[usd_import]") {
  Scene scene = importFile(kDir + "animated.usda");
  scene.stage.find("/World/Box")->behaviors().push_back("pinOnEvenUpdates");
  const Stage beforePlay = scene.stage;
  BehaviorRegistry registry = registryWithPin();
  BehaviorRuntime runtime(scene.stage, registry, BehaviorContext{});
  runtime.init();
  runtime.play();
  for (int step = 1; step <= 6; ++step) {
    runtime.update();
    INFO("update " << step);
    if (step % 2 == 0) CHECK(translate(scene.stage, "/World/Box") == Vec3d(9, 9, 9));
    else CHECK(translate(scene.stage, "/World/Box").isApprox(Vec3d(-1.6 + 0.4 * step, 0, 0.5)));
  }
  runtime.stop();
  CHECK(scene.stage == beforePlay);
}

TEST_CASE("usd animation: layer offsets, held values and the interpolation of each type", "[usd_import]") {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sdg_usd_animation_test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "anim.usda") << R"(#usda 1.0
(
    metersPerUnit = 1
    upAxis = "Z"
)
def Xform "Anim" {
    float3 xformOp:rotateXYZ.timeSamples = { 0: (0, 0, 0), 10: (0, 0, 90) }
    quatf xformOp:orient.timeSamples = { 0: (1, 0, 0, 0), 10: (0, 0, 0, 1) }
    uniform token[] xformOpOrder = ["xformOp:rotateXYZ", "xformOp:orient"]
}
)";
  std::ofstream(dir / "root.usda") << R"(#usda 1.0
(
    metersPerUnit = 1
    upAxis = "Z"
    startTimeCode = 4
    timeCodesPerSecond = 2
)
def Xform "World" {
    def Xform "Late" (references = @anim.usda@</Anim> (offset = 4; scale = 0.5)) {}
    def Camera "Cam" {
        float focalLength.timeSamples = { 4: 20, 6: 60 }
        token projection.timeSamples = { 4: "perspective", 5: "orthographic" }
    }
}
)";
  Scene scene = importFile((dir / "root.usda").string());
  // Layer time 0..10 at offset 4, scale 0.5: stage time codes 4..9.
  const AnimatedValue* rot = scene.stage.animation().find("/World/Late", "xformOp:rotateXYZ");
  REQUIRE(rot);
  CHECK(rot->times == std::vector<double>{4, 9});
  CHECK(rot->clock.startTimeCode == 4);
  CHECK(rot->clock.timeCodesPerSecond == 2);
  CHECK(rot->at(6.5).get<Vec3d>().isApprox(Vec3d(0, 0, 45)));
  const Quatd q = scene.stage.animation().find("/World/Late", "xformOp:orient")->at(6.5).get<Quatd>();
  CHECK(std::abs(q.w()) == Approx(std::sqrt(0.5)));  // slerp half way to a half turn
  CHECK(std::abs(q.z()) == Approx(std::sqrt(0.5)));
  const AnimatedValue* focal = scene.stage.animation().find("/World/Cam", "focalLength");
  REQUIRE(focal);
  CHECK(focal->at(5).get<float>() == 40.0f);
  const AnimatedValue* projection = scene.stage.animation().find("/World/Cam", "projection");
  REQUIRE(projection);
  CHECK(projection->at(4.99).get<std::string>() == "perspective");
  CHECK(projection->at(5).get<std::string>() == "orthographic");
  // The timeline at 2 updates a second lands on whole time codes: update n shows 4 + n.
  CHECK(timeCodeAt(rot->clock, 3, 2.0) == 7.0);
  bool whole = true;
  for (uint64_t n = 0; n < 100000; ++n) whole = whole && timeCodeAt(AnimationClock{0, 24}, n, 24.0) == double(n);
  CHECK(whole);
  std::filesystem::remove_all(dir);
}

}  // namespace sdg
