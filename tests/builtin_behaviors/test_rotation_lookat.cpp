#include "behavior/behavior_fixtures.h"

#include <cmath>

#include "stage/look_at.h"
#include "stage/xform_edit.h"

using namespace sdg;

namespace {
double angleBetween(const Vec3d& a, const Vec3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}
// The world direction of the prim's local -Z.
Vec3d viewDirection(const Stage& stage, const Prim& p) {
  return -(worldRotation(stage, p) * Vec3d::UnitZ());
}
}  // namespace

TEST_CASE("rotationRandomizer: X then Y then Z, written into the op's own axis order", "[behaviors][rotation]") {
  test::BehaviorScene s(R"(
version: 1
prims:
  /Zyx: {type: Cube, rotateZYX: [0, 0, 0], behaviors: {rotationRandomizer: {}}}
  /Orient: {type: Cube, orient: [1, 0, 0, 0], behaviors: {rotationRandomizer: {}}}
  /None: {type: Cube, translate: [1, 2, 3], behaviors: {rotationRandomizer: {}}}
)");
  s.runtime->play();
  s.runtime->update();
  for (const char* path : {"/Zyx", "/Orient", "/None"}) {
    CAPTURE(path);
    Rng rng = makeBehaviorRng(0, path, "rotationRandomizer", 0, -1);
    Vec3d angles;
    for (int a = 0; a < 3; ++a) angles[a] = rng.uniform(0, 360);
    Matrix3d expected = axisRotation(2, angles.z()) * axisRotation(1, angles.y()) * axisRotation(0, angles.x());
    CHECK(s.stage().worldMatrix(s.prim(path)).block<3, 3>(0, 0).isApprox(expected, 1e-12));
  }
  // The prim without a rotation op got an orient after its translate.
  CHECK(s.prim("/None").xformOps()[1].attributeName() == "xformOp:orient");
}

TEST_CASE("rotationRandomizer: angles stay in their ranges", "[behaviors][rotation]") {
  test::BehaviorScene s(R"(
version: 1
prims:
  /A: {type: Cube, rotateXYZ: [0, 0, 0], behaviors: {rotationRandomizer: {range:minRotation: [0, 0, -30], range:maxRotation: [0, 0, 30]}}}
)");
  s.runtime->play();
  for (int i = 0; i < 2000; ++i) {
    s.runtime->update();
    Vec3d v = s.prim("/A").xformOps()[0].value.get<Vec3d>();
    REQUIRE(std::fabs(v.x()) < 1e-9);
    REQUIRE(std::fabs(v.y()) < 1e-9);
    REQUIRE(v.z() >= -30 - 1e-9);
    REQUIRE(v.z() <= 30 + 1e-9);
  }
}

TEST_CASE("look-at math: -Z points at the target within 1e-9 rad, +Y up", "[behaviors][lookat]") {
  const Vec3d eye(1, -2, 3);
  const Vec3d targets[] = {{5, 5, 5}, {1, -2, 10} /* straight above */, {1, -2, -4} /* below */, {-3, 0.5, 3}};
  for (const Vec3d& target : targets) {
    CAPTURE(target.transpose());
    auto R = lookAtRotation(eye, target, Vec3d::UnitZ());
    REQUIRE(R);
    CHECK(angleBetween(-(*R * Vec3d::UnitZ()), target - eye) < 1e-9);
    CHECK((R->transpose() * *R).isApprox(Matrix3d::Identity(), 1e-12));
    CHECK(R->determinant() > 0.999999);
    Vec3d up = *R * Vec3d::UnitY();
    if ((target - eye).normalized().cross(Vec3d::UnitZ()).norm() > 1e-6) CHECK(up.z() > 0);  // horizon level
  }
  CHECK_FALSE(lookAtRotation(eye, eye, Vec3d::UnitZ()));
}

TEST_CASE("lookAtBehavior: aims at a moving target, also under a rotated parent", "[behaviors][lookat]") {
  test::BehaviorScene s(R"(
version: 1
prims:
  /Target:
    type: Sphere
    translate: [3, 4, 1]
    behaviors: {locationRandomizer: {}}
  /Rig: {rotateXYZ: [10, 20, 30], translate: [0, 0, 0]}
  /Rig/Camera:
    type: Camera
    translate: [0, -5, 2]
    behaviors: {lookAtBehavior: {targetPrimPath: /Target}}
)");
  s.runtime->play();
  for (int i = 0; i < 20; ++i) {
    s.runtime->update();
    const Prim& cam = s.prim("/Rig/Camera");
    Vec3d toTarget = worldLocation(s.stage(), s.prim("/Target")) - worldLocation(s.stage(), cam);
    CHECK(angleBetween(viewDirection(s.stage(), cam), toTarget) < 1e-9);
  }
}

TEST_CASE("lookAtBehavior: a target straight above the camera is still hit exactly", "[behaviors][lookat]") {
  test::BehaviorScene s(R"(
version: 1
prims:
  /Camera:
    type: Camera
    translate: [1, 1, 0]
    behaviors: {lookAtBehavior: {targetLocation: [1, 1, 50]}}
)");
  s.runtime->play();
  s.runtime->update();
  CHECK(angleBetween(viewDirection(s.stage(), s.prim("/Camera")), Vec3d::UnitZ()) < 1e-9);
}
