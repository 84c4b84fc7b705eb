#include "behavior/behavior_fixtures.h"

#include <cmath>

using namespace sdg;

namespace {
// The stream a behavior on `prim` draws from, for hand computations.
Rng streamOf(const std::string& prim, const std::string& behavior, int64_t seed = 0) {
  return makeBehaviorRng(seed, prim, behavior, 0, -1);
}
Vec3d draw(Rng& rng, const Vec3d& lo, const Vec3d& hi) {
  Vec3d o;
  for (int a = 0; a < 3; ++a) o[a] = rng.uniform(lo[a], hi[a]);
  return o;
}
}  // namespace

TEST_CASE("locationRandomizer: 10,000 draws stay in range, centred, axes independent", "[behaviors][location]") {
  test::BehaviorScene s(R"(
version: 1
prims:
  /Box:
    type: Cube
    behaviors:
      locationRandomizer: {frame:useRelativeFrame: false, range:minPosition: [-1, 2, 10], range:maxPosition: [3, 4, 10.5]}
)");
  const Vec3d lo(-1, 2, 10), hi(3, 4, 10.5);
  s.runtime->play();
  const int n = 10000;
  Vec3d sum = Vec3d::Zero();
  double sumXY = 0;
  for (int i = 0; i < n; ++i) {
    s.runtime->update();
    Vec3d p = s.translate("/Box");
    for (int a = 0; a < 3; ++a) {
      REQUIRE(p[a] >= lo[a]);
      REQUIRE(p[a] <= hi[a]);
    }
    sum += p;
    sumXY += (p.x() - 1.0) * (p.y() - 3.0);
  }
  Vec3d mean = sum / n;
  for (int a = 0; a < 3; ++a) {
    double sigma = (hi[a] - lo[a]) / std::sqrt(12.0);
    CHECK(std::fabs(mean[a] - (lo[a] + hi[a]) / 2) < 4 * sigma / std::sqrt(double(n)));
  }
  // Correlation of x and y near zero: |r| < 4 / sqrt(n).
  double r = (sumXY / n) / ((4 / std::sqrt(12.0)) * (2 / std::sqrt(12.0)));
  CHECK(std::fabs(r) < 4 / std::sqrt(double(n)));
}

TEST_CASE("locationRandomizer: the four formulas against hand computation", "[behaviors][location]") {
  const Vec3d lo(-0.5, -0.5, -0.5), hi(0.5, 0.5, 0.5);
  auto run = [](const std::string& yamlBehaviors) {
    auto s = std::make_unique<test::BehaviorScene>(R"(
version: 1
prims:
  /Target: {type: Sphere, translate: [10, 20, 30]}
  /Box:
    type: Cube
    translate: [1, 2, 3]
    behaviors:
      locationRandomizer: )" + yamlBehaviors + "\n");
    s->runtime->play();
    s->runtime->update();
    return s;
  };
  SECTION("no target, relative: initial + o") {
    auto s = run("{range:minPosition: [-0.5,-0.5,-0.5], range:maxPosition: [0.5,0.5,0.5]}");
    Rng rng = streamOf("/Box", "locationRandomizer");
    CHECK(s->translate("/Box").isApprox(Vec3d(1, 2, 3) + draw(rng, lo, hi), 1e-15));
  }
  SECTION("no target, absolute: o") {
    auto s = run("{frame:useRelativeFrame: false, range:minPosition: [-0.5,-0.5,-0.5], range:maxPosition: [0.5,0.5,0.5]}");
    Rng rng = streamOf("/Box", "locationRandomizer");
    CHECK(s->translate("/Box").isApprox(draw(rng, lo, hi), 1e-15));
  }
  SECTION("target, relative: target + initial offset + o") {
    auto s = run("{frame:targetPrimPath: /Target, range:minPosition: [-0.5,-0.5,-0.5], range:maxPosition: [0.5,0.5,0.5]}");
    Rng rng = streamOf("/Box", "locationRandomizer");
    Vec3d offset = Vec3d(1, 2, 3) - Vec3d(10, 20, 30);
    CHECK(s->translate("/Box").isApprox(Vec3d(10, 20, 30) + offset + draw(rng, lo, hi), 1e-15));
  }
  SECTION("target, absolute: target + o") {
    auto s = run("{frame:targetPrimPath: /Target, frame:useRelativeFrame: false, range:minPosition: [-0.5,-0.5,-0.5], range:maxPosition: [0.5,0.5,0.5]}");
    Rng rng = streamOf("/Box", "locationRandomizer");
    CHECK(s->translate("/Box").isApprox(Vec3d(10, 20, 30) + draw(rng, lo, hi), 1e-15));
  }
}

TEST_CASE("locationRandomizer: with a target under a moved parent the world position is exact",
          "[behaviors][location]") {
  test::BehaviorScene s(R"(
version: 1
prims:
  /Target: {type: Sphere, translate: [10, 0, 0]}
  /Parent: {translate: [0, 5, 0], rotateZ: 90, scale: [2, 2, 2]}
  /Parent/Box:
    type: Cube
    behaviors:
      locationRandomizer: {frame:targetPrimPath: /Target, frame:useRelativeFrame: false, range:minPosition: [1, 1, 1], range:maxPosition: [1, 1, 1]}
)");
  s.runtime->play();
  s.runtime->update();
  Vec3d world = s.stage().worldMatrix(s.prim("/Parent/Box")).block<3, 1>(0, 3);
  CHECK(world.isApprox(Vec3d(11, 1, 1), 1e-12));
}

TEST_CASE("locationRandomizer: includeChildren moves parent and child and the offsets compound", "[behaviors][location]") {
  test::BehaviorScene s(R"(
version: 1
prims:
  /Group:
    translate: [0, 0, 0]
    behaviors:
      locationRandomizer: {frame:useRelativeFrame: false, range:minPosition: [1, 1, 1], range:maxPosition: [1, 1, 1]}
  /Group/Child: {type: Cube, translate: [0, 0, 0]}
)");
  s.runtime->play();
  s.runtime->update();
  CHECK(s.translate("/Group") == Vec3d(1, 1, 1));
  CHECK(s.translate("/Group/Child") == Vec3d(1, 1, 1));
  CHECK(s.stage().worldMatrix(s.prim("/Group/Child")).block<3, 1>(0, 3) == Vec3d(2, 2, 2));
}

TEST_CASE("locationRandomizer: a prim without a translate op gets one, removed on stop", "[behaviors][location]") {
  test::BehaviorScene s(R"(
version: 1
prims:
  /Box: {type: Cube, rotateZ: 45, behaviors: {locationRandomizer: {}}}
)");
  Stage before = s.stage();
  s.runtime->play();
  s.runtime->update();
  const auto& ops = s.prim("/Box").xformOps();
  REQUIRE(ops.size() == 2);
  CHECK(ops[0].attributeName() == "xformOp:translate");  // inserted first: a parent-frame translation
  s.runtime->stop();
  CHECK(s.stage() == before);
}

TEST_CASE("random streams: adding a behavior on another prim changes nothing this one draws",
          "[behaviors][determinism]") {
  const std::string base = R"(
version: 1
prims:
  /A: {type: Cube, behaviors: {locationRandomizer: {}}}
)";
  auto positions = [](const std::string& yaml) {
    test::BehaviorScene s(yaml, 42);
    s.runtime->play();
    std::vector<Vec3d> out;
    for (int i = 0; i < 5; ++i) {
      s.runtime->update();
      out.push_back(s.translate("/A"));
    }
    return out;
  };
  auto alone = positions(base);
  auto withOthers = positions(base + "  /B: {type: Cube, behaviors: {locationRandomizer: {}, rotationRandomizer: {}}}\n"
                                     "  /C: {type: SphereLight, behaviors: {lightRandomizer: {}}}\n");
  CHECK(alone == withOthers);
  auto otherSeed = [&] {
    test::BehaviorScene s(base, 43);
    s.runtime->play();
    s.runtime->update();
    return s.translate("/A");
  }();
  CHECK(otherSeed != alone[0]);
}

TEST_CASE("random streams: a fixed seed replays the same sequence after stop", "[behaviors][determinism]") {
  test::BehaviorScene s("version: 1\nprims:\n  /A: {type: Cube, behaviors: {locationRandomizer: {seed: 7}}}\n");
  s.runtime->play();
  s.runtime->update();
  Vec3d first = s.translate("/A");
  s.runtime->stop();
  s.runtime->play();
  s.runtime->update();
  CHECK(s.translate("/A") == first);
}
