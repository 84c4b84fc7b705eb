// The volume stack randomizer end to end on small scenes: the stacks it
// builds are checked with geometry computed here (oriented boxes from the
// prims' poses), not with numbers the physics code reports about itself.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>

#include "behavior/behavior_fixtures.h"
#include "core/diagnostics.h"
#include "physics/collider.h"
#include "physics/convex_hull.h"
#include "physics/physics_settings.h"
#include "run/preroll.h"

using namespace sdg;

namespace {

constexpr const char* kIn = "isaacsim.replicator.behavior.volumeStackRandomizer.in";
constexpr const char* kOut = "isaacsim.replicator.behavior.volumeStackRandomizer.out";

std::string stackScene(const std::string& assets, const std::string& range, int seed = -1) {
  return "version: 1\n"
         "prims:\n"
         "  /World: {}\n"
         "  /World/Pallets:\n"
         "    behaviors:\n"
         "      volumeStackRandomizer: {assets:csv: \"" + assets + "\", assets:numRange: " + range +
         ", dropHeight: 1.2, renderSimulation: false, seed: " + std::to_string(seed) + "}\n"
         "  /World/Pallets/A: {type: Cube, translate: [-1, 0, 0.07], scale: [0.6, 0.5, 0.07]}\n"
         "  /World/Pallets/B: {type: Cube, translate: [1, 0.3, 0.07], rotateXYZ: [0, 0, 30], scale: [0.6, 0.5, 0.07]}\n";
}

struct StackFixture {
  AssetResolver assets{{SDG_SOURCE_DIR "/tests/data/meshes", SDG_SOURCE_DIR "/scenes"}};
  PhysicsSettings physics;
  std::vector<nlohmann::ordered_json> reports;
  std::vector<Payload> replies;
  test::BehaviorScene behaviors;
  Scene& scene;
  BehaviorRuntime* runtime;

  explicit StackFixture(const std::string& yaml, int64_t seed = 0)
      : behaviors(yaml, seed,
                  [this](BehaviorContext& context) {
                    context.assets = &assets;
                    context.physics = &physics;
                    context.hooks.report = [this](const std::string&, const nlohmann::ordered_json& r) {
                      reports.push_back(r);
                    };
                  }),
        scene(behaviors.scene),
        runtime(behaviors.runtime.get()) {
    // INIT is delivered on the first update, so subscribing here still sees it.
    runtime->events().subscribe(kOut, [this](const Payload& p) { replies.push_back(p); });
  }
  // Publishes an action and runs updates until the reply arrives.
  void act(const std::string& action, const std::string& prim = "") {
    Payload p{{"action", action}};
    if (!prim.empty()) p.set("prim_path", prim);
    runtime->events().publish(kIn, p);
    for (int i = 0; i < 3; ++i) runtime->update();
  }
  void stack() {
    act("reset");
    act("setup");
    act("run");
  }
  std::vector<const Prim*> assetsOf(const std::string& surfaceName) const {
    std::vector<const Prim*> out;
    const Prim* root = scene.stage.find("/Behaviors/volumeStackRandomizer/Assets/" + surfaceName);
    if (root)
      for (const Prim* c : root->children()) out.push_back(c);
    return out;
  }
};

// An asset's collision box in world space, from its prim pose.
struct Obb {
  Vec3d centre;
  Matrix3d axes;  // columns
  Vec3d half;
};

Obb obbOf(const Stage& stage, const Prim& prim, const AssetResolver& assets) {
  auto collider = ColliderCache::shared().get(meshKeyOf(prim, stage.metadata().subdivisionLevel), assets, prim.path());
  Matrix4d m = stage.worldMatrix(prim);
  Obb box;
  box.axes = m.topLeftCorner<3, 3>();
  box.centre = (m * collider->bounds.center().homogeneous()).head<3>();
  box.half = collider->bounds.sizes() / 2;
  return box;
}

// Penetration depth of two boxes along their separating-axis candidates
// (the smallest overlap; <= 0 means apart).
double overlap(const Obb& a, const Obb& b) {
  std::vector<Vec3d> axes;
  for (int i = 0; i < 3; ++i) axes.push_back(a.axes.col(i)), axes.push_back(b.axes.col(i));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Vec3d c = a.axes.col(i).cross(b.axes.col(j));
      if (c.norm() > 1e-6) axes.push_back(c.normalized());
    }
  double smallest = 1e300;
  for (const Vec3d& n : axes) {
    auto radius = [&](const Obb& o) {
      double r = 0;
      for (int k = 0; k < 3; ++k) r += o.half[k] * std::abs(o.axes.col(k).dot(n));
      return r;
    };
    double d = radius(a) + radius(b) - std::abs((b.centre - a.centre).dot(n));
    smallest = std::min(smallest, d);
  }
  return smallest;
}

double lowestZ(const Obb& o) {
  double z = o.centre.z();
  for (int k = 0; k < 3; ++k) z -= o.half[k] * std::abs(o.axes(2, k));
  return z;
}

std::vector<std::pair<Vec3d, Eigen::Quaterniond>> posesOf(const StackFixture& f, const std::string& surface) {
  std::vector<std::pair<Vec3d, Eigen::Quaterniond>> out;
  for (const Prim* p : f.assetsOf(surface))
    out.push_back({p->xformOps().at(0).value.get<Vec3d>(), p->xformOps().at(1).value.get<Quatd>()});  // translate, orient
  return out;
}

}  // namespace

TEST_CASE("convex hull: a cube has 6 faces and its volume, flat input has none", "[physics]") {
  std::vector<Vec3f> cube;
  for (int c = 0; c < 8; ++c) cube.push_back(Vec3f(c & 1 ? 1.f : 0.f, c & 2 ? 2.f : 0.f, c & 4 ? 3.f : 0.f));
  cube.push_back(Vec3f(0.5f, 1.f, 1.5f));  // an interior point is dropped
  auto hull = computeConvexHull(cube);
  REQUIRE(hull);
  CHECK(hull->faceCount == 6);
  CHECK(hull->pointCount() == 8);
  CHECK(hull->volume == Approx(6.0));
  CHECK((hull->centroid - Vec3d(0.5, 1, 1.5)).norm() < 1e-9);
  // Every plane has every point on its inner side.
  for (size_t f = 0; f < hull->faceCount; ++f)
    for (size_t p = 0; p < hull->pointCount(); ++p) {
      Vec3d n(hull->planes[4 * f], hull->planes[4 * f + 1], hull->planes[4 * f + 2]);
      Vec3d x(hull->points[3 * p], hull->points[3 * p + 1], hull->points[3 * p + 2]);
      CHECK(n.dot(x) <= hull->planes[4 * f + 3] + 1e-9);
    }
  std::string why;
  std::vector<Vec3f> flat = {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(0, 1, 0), Vec3f(1, 1, 0)};
  CHECK_FALSE(computeConvexHull(flat, &why));
  CHECK_FALSE(why.empty());
}

TEST_CASE("stacking: assets rest on the surface or each other, apart, inside the walls, still", "[physics]") {
  StackFixture f(stackScene("crate.glb#crate", "[6, 9]"), 7);
  f.stack();
  REQUIRE(f.reports.size() == 2);  // two surfaces at once
  for (const char* surface : {"A", "B"}) {
    CAPTURE(surface);
    const Prim& pallet = *f.scene.stage.find(std::string("/World/Pallets/") + surface);
    const Matrix4d palletWorld = f.scene.stage.worldMatrix(pallet);
    const double top = 0.14;
    std::vector<const Prim*> assets = f.assetsOf(surface);
    REQUIRE(assets.size() >= 6);
    REQUIRE(assets.size() <= 9);
    std::vector<Obb> boxes;
    for (const Prim* a : assets) {
      CHECK(a->semantics().at("class") == std::vector<std::string>{"crate"});
      boxes.push_back(obbOf(f.scene.stage, *a, f.assets));
    }
    for (size_t i = 0; i < boxes.size(); ++i) {
      CAPTURE(assets[i]->path());
      CHECK(lowestZ(boxes[i]) > top - 0.005);  // not sunk more than 5 mm
      // Inside the walled footprint (1.2 x 1.0 in the pallet's axes), 1 cm slack.
      Vec3d local = palletWorld.topLeftCorner<3, 3>().colwise().normalized().transpose() *
                    (boxes[i].centre - palletWorld.topRightCorner<3, 1>());
      CHECK(std::abs(local.x()) < 0.6 + 0.01);
      CHECK(std::abs(local.y()) < 0.5 + 0.01);
      for (size_t j = i + 1; j < boxes.size(); ++j) CHECK(overlap(boxes[i], boxes[j]) < 0.01);
    }
  }
  for (const auto& r : f.reports) {
    CHECK(r["settled"].get<bool>());
    CHECK(r["max_linear_speed"].get<double>() <= f.physics.settleLinearSpeed);
    CHECK(r["max_angular_speed"].get<double>() <= f.physics.settleAngularSpeed);
    CHECK(r["left_area"].empty());
  }
  // Walls are gone after the run; the assets stay.
  CHECK(f.scene.stage.find("/Behaviors/volumeStackRandomizer/CollisionWalls") == nullptr);
}

TEST_CASE("stacking: the same seed gives bitwise the same poses, another seed others", "[physics][determinism]") {
  auto run = [](int64_t seed) {
    StackFixture f(stackScene("crate.glb#crate", "[4, 6]"), seed);
    f.stack();
    return std::make_pair(posesOf(f, "A"), posesOf(f, "B"));
  };
  auto a = run(3), b = run(3), c = run(4);
  REQUIRE(a.first.size() == b.first.size());
  for (size_t i = 0; i < a.first.size(); ++i) {
    CHECK(a.first[i].first == b.first[i].first);  // exact, not approximate
    CHECK(a.first[i].second.coeffs() == b.first[i].second.coeffs());
  }
  CHECK(a.second.size() == b.second.size());
  bool differs = a.first.size() != c.first.size();
  for (size_t i = 0; !differs && i < a.first.size(); ++i) differs = a.first[i].first != c.first[i].first;
  CHECK(differs);
}

TEST_CASE("stacking: assets from every mesh format stack", "[physics]") {
  for (const char* file : {"crate.obj", "crate.glb", "crate.gltf", "crate.fbx", "crate.ply", "crate.stl", "crate.dae"}) {
    CAPTURE(file);
    StackFixture f(stackScene(file, "[3, 3]"), 1);
    f.stack();
    REQUIRE(f.assetsOf("A").size() == 3);
    for (const Prim* a : f.assetsOf("A")) CHECK(lowestZ(obbOf(f.scene.stage, *a, f.assets)) > 0.14 - 0.005);
    for (const auto& r : f.reports) CHECK(r["settled"].get<bool>());
  }
}

TEST_CASE("stacking: the event protocol answers in order, per prim, and reset removes everything", "[physics][events]") {
  StackFixture f(stackScene("crate.glb", "[2, 2]"), 1);
  const Stage before = f.scene.stage;
  f.runtime->update();  // delivers INIT
  REQUIRE(f.replies.size() == 1);
  CHECK(f.replies[0].getString("state_name") == "INIT");
  f.replies.clear();
  f.act("setup", "/World/Other");  // addressed to another prim: ignored
  CHECK(f.replies.empty());
  f.act("setup", "/World/Pallets");
  f.act("run");
  f.act("nonsense");  // unknown actions are ignored
  std::vector<std::string> states;
  for (const Payload& p : f.replies) {
    CHECK(p.getString("prim_path") == "/World/Pallets");
    states.emplace_back(p.getString("state_name"));
  }
  CHECK(states == std::vector<std::string>{"SETUP", "RUNNING", "FINISHED"});
  CHECK(f.assetsOf("A").size() == 2);
  CHECK(f.assetsOf("A")[0]->semantics().at("class") == std::vector<std::string>{"crate"});  // label from the file name
  f.act("reset");
  CHECK(f.replies.back().getString("state_name") == "RESET");
  CHECK(f.scene.stage == before);
}

TEST_CASE("pre-roll: a reply that never comes times out naming the event, the state and the prim", "[physics][events]") {
  StackFixture f(stackScene("crate.glb", "[1, 1]"), 1);
  EventStep step;
  step.publish = kIn;
  step.payload = Payload{{"action", "setup"}, {"prim_path", "/World/Pallets"}};
  step.waitEvent = kOut;
  step.waitFor = Payload{{"state_name", "FINISHED"}};  // setup answers SETUP, never FINISHED
  step.maxUpdates = 4;
  try {
    runPreroll(std::span<const EventStep>(&step, 1), *f.runtime);
    FAIL("no timeout");
  } catch (const RunError& e) {
    std::string m = e.what();
    CHECK_THAT(m, Catch::Contains(kIn));
    CHECK_THAT(m, Catch::Contains("FINISHED"));
    CHECK_THAT(m, Catch::Contains("within 4 updates"));
    CHECK_THAT(m, Catch::Contains("prim: /World/Pallets"));
  }
}

TEST_CASE("stacking: require_settled turns a stack that cannot settle into an error", "[physics]") {
  StackFixture f(stackScene("crate.glb", "[8, 8]"), 1);
  f.physics.maxSettleSteps = 0;
  f.physics.settleLinearSpeed = 0;  // nothing is ever that still
  f.physics.settleAngularSpeed = 0;
  f.physics.requireSettled = true;
  f.act("setup");
  f.runtime->events().publish(kIn, Payload{{"action", "run"}});
  CHECK_THROWS_WITH(f.runtime->update(), Catch::Contains("require_settled"));
}
