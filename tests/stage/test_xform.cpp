// Transform ops against hand-computed matrices.
#include <catch2/catch.hpp>

#include <cmath>

#include "stage/stage.h"
#include "stage/xform.h"

using namespace sdg;

namespace {
constexpr double kTol = 1e-12;

XformOp op(XformOpKind kind, Value v) {
  XformOp o;
  o.kind = kind;
  o.value = std::move(v);
  return o;
}

Vec3d apply(const Matrix4d& m, const Vec3d& p) { return (m * p.homogeneous()).head<3>(); }
}  // namespace

TEST_CASE("xform: translate, rotateXYZ, scale apply scale first and translate last", "[stage][xform]") {
  std::vector<XformOp> ops = {op(XformOpKind::Translate, Value::makeDouble3({1, 2, 3})),
                              op(XformOpKind::RotateXYZ, Value::makeDouble3({0, 0, 90})),
                              op(XformOpKind::Scale, Value::makeDouble3({2, 2, 2}))};
  // (1,0,0) scaled -> (2,0,0), rotated 90 deg about Z -> (0,2,0), translated -> (1,4,3).
  Vec3d p = apply(localMatrix(ops), {1, 0, 0});
  CHECK(p.isApprox(Vec3d(1, 4, 3), kTol));
}

TEST_CASE("xform: rotateXYZ applies X first, rotateZYX applies Z first", "[stage][xform]") {
  // Point (0,1,0). XYZ (90, 0, 90): X90 -> (0,0,1); Z90 leaves it -> (0,0,1).
  Matrix4d xyz = op(XformOpKind::RotateXYZ, Value::makeDouble3({90, 0, 90})).matrix();
  CHECK(apply(xyz, {0, 1, 0}).isApprox(Vec3d(0, 0, 1), kTol));
  // ZYX (90, 0, 90): Z90 -> (-1,0,0); X90 leaves it -> (-1,0,0).
  Matrix4d zyx = op(XformOpKind::RotateZYX, Value::makeDouble3({90, 0, 90})).matrix();
  CHECK(apply(zyx, {0, 1, 0}).isApprox(Vec3d(-1, 0, 0), kTol));
}

TEST_CASE("xform: single-axis rotates, orient and transform", "[stage][xform]") {
  Matrix4d rx = op(XformOpKind::RotateX, Value::makeDouble(90)).matrix();
  CHECK(apply(rx, {0, 1, 0}).isApprox(Vec3d(0, 0, 1), kTol));
  Matrix4d ry = op(XformOpKind::RotateY, Value::makeDouble(90)).matrix();
  CHECK(apply(ry, {0, 0, 1}).isApprox(Vec3d(1, 0, 0), kTol));
  // 90 degrees about Z as a quaternion (w, x, y, z).
  double h = std::sqrt(0.5);
  Matrix4d orient = op(XformOpKind::Orient, Value::makeQuatd(Quatd(h, 0, 0, h))).matrix();
  CHECK(apply(orient, {1, 0, 0}).isApprox(Vec3d(0, 1, 0), kTol));
  Matrix4d t = Matrix4d::Identity();
  t(0, 3) = 5;
  CHECK(apply(op(XformOpKind::Transform, Value::makeMatrix4d(t)).matrix(), {1, 1, 1}).isApprox(Vec3d(6, 1, 1), kTol));
}

TEST_CASE("xform: Euler decomposition reproduces the rotation for every order", "[stage][xform]") {
  const Vec3d angles(30, -50, 120);
  for (XformOpKind kind : allXformOpKinds()) {
    if (!isThreeAxisRotate(kind)) continue;
    CAPTURE(xformOpKindName(kind));
    Matrix3d R = rotationFromEuler(kind, angles);
    Vec3d back = eulerFromRotation(kind, R);
    CHECK(rotationFromEuler(kind, back).isApprox(R, 1e-12));
  }
}

TEST_CASE("xform: decompose and compose keep translation, rotation and scale", "[stage][xform]") {
  Matrix3d R = rotationFromEuler(XformOpKind::RotateXYZ, {10, 20, 30});
  Matrix4d m = compose({1, 2, 3}, R, {2, 3, 4});
  Decomposed d = decompose(m);
  CHECK(d.translation.isApprox(Vec3d(1, 2, 3), kTol));
  CHECK(d.rotation.isApprox(R, 1e-12));
  CHECK(d.scale.isApprox(Vec3d(2, 3, 4), 1e-12));
}

TEST_CASE("xform: nested prims compose parent then child", "[stage][xform]") {
  Stage stage;
  Prim& parent = stage.definePrim("/P", PrimType::Xform);
  parent.xformOps().push_back(op(XformOpKind::Translate, Value::makeDouble3({10, 0, 0})));
  parent.xformOps().push_back(op(XformOpKind::RotateZ, Value::makeDouble(90)));
  Prim& child = stage.definePrim("/P/C", PrimType::Cube);
  child.xformOps().push_back(op(XformOpKind::Translate, Value::makeDouble3({1, 0, 0})));
  // Child origin: (1,0,0) rotated 90 about Z -> (0,1,0), + (10,0,0) -> (10,1,0).
  Vec3d origin = stage.worldMatrix(child).block<3, 1>(0, 3);
  CHECK(origin.isApprox(Vec3d(10, 1, 0), kTol));
}

TEST_CASE("xform: op names parse with suffixes", "[stage][xform]") {
  auto o = parseXformOpName("xformOp:translate:pivot");
  REQUIRE(o);
  CHECK(o->kind == XformOpKind::Translate);
  CHECK(o->suffix == "pivot");
  CHECK(o->attributeName() == "xformOp:translate:pivot");
  CHECK_FALSE(parseXformOpName("xformOp:spin"));
  CHECK_FALSE(parseXformOpName("translate"));
}
