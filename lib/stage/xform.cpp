#include "stage/xform.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace sdg {
namespace {
struct KindInfo {
  XformOpKind kind;
  std::string_view name;
  std::array<int, 3> axes;  // application order of the three-axis rotates
};
constexpr std::array kKinds = {
    KindInfo{XformOpKind::Translate, "translate", {}},
    KindInfo{XformOpKind::Scale, "scale", {}},
    KindInfo{XformOpKind::RotateX, "rotateX", {}},
    KindInfo{XformOpKind::RotateY, "rotateY", {}},
    KindInfo{XformOpKind::RotateZ, "rotateZ", {}},
    KindInfo{XformOpKind::RotateXYZ, "rotateXYZ", {0, 1, 2}},
    KindInfo{XformOpKind::RotateXZY, "rotateXZY", {0, 2, 1}},
    KindInfo{XformOpKind::RotateYXZ, "rotateYXZ", {1, 0, 2}},
    KindInfo{XformOpKind::RotateYZX, "rotateYZX", {1, 2, 0}},
    KindInfo{XformOpKind::RotateZXY, "rotateZXY", {2, 0, 1}},
    KindInfo{XformOpKind::RotateZYX, "rotateZYX", {2, 1, 0}},
    KindInfo{XformOpKind::Orient, "orient", {}},
    KindInfo{XformOpKind::Transform, "transform", {}},
};
constexpr std::array<XformOpKind, kKinds.size()> kKindList = [] {
  std::array<XformOpKind, kKinds.size()> list{};
  for (size_t i = 0; i < kKinds.size(); ++i) list[i] = kKinds[i].kind;
  return list;
}();

const KindInfo& info(XformOpKind kind) {
  for (const KindInfo& k : kKinds)
    if (k.kind == kind) return k;
  return kKinds[0];
}

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }
double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }
}  // namespace

std::span<const XformOpKind> allXformOpKinds() { return kKindList; }
std::string_view xformOpKindName(XformOpKind kind) { return info(kind).name; }

std::optional<XformOpKind> xformOpKindFromName(std::string_view name) {
  for (const KindInfo& k : kKinds)
    if (k.name == name) return k.kind;
  return std::nullopt;
}

ValueType xformOpValueType(XformOpKind kind) {
  switch (kind) {
    case XformOpKind::RotateX:
    case XformOpKind::RotateY:
    case XformOpKind::RotateZ: return ValueType::Double;
    case XformOpKind::Orient: return ValueType::Quatd;
    case XformOpKind::Transform: return ValueType::Matrix4d;
    default: return ValueType::Double3;
  }
}

bool isRotateKind(XformOpKind kind) { return kind >= XformOpKind::RotateX && kind <= XformOpKind::RotateZYX; }
bool isThreeAxisRotate(XformOpKind kind) { return kind >= XformOpKind::RotateXYZ && kind <= XformOpKind::RotateZYX; }

std::string XformOp::attributeName() const {
  std::string name = "xformOp:" + std::string(xformOpKindName(kind));
  if (!suffix.empty()) name += ":" + suffix;
  return name;
}

std::optional<XformOp> parseXformOpName(std::string_view attributeName) {
  constexpr std::string_view kPrefix = "xformOp:";
  if (attributeName.substr(0, kPrefix.size()) != kPrefix) return std::nullopt;
  std::string_view rest = attributeName.substr(kPrefix.size());
  size_t colon = rest.find(':');
  auto kind = xformOpKindFromName(rest.substr(0, colon));
  if (!kind) return std::nullopt;
  XformOp op;
  op.kind = *kind;
  if (colon != std::string_view::npos) op.suffix = std::string(rest.substr(colon + 1));
  return op;
}

Matrix3d axisRotation(int axis, double deg) {
  static const Vec3d kAxes[3] = {Vec3d::UnitX(), Vec3d::UnitY(), Vec3d::UnitZ()};
  return Eigen::AngleAxisd(radians(deg), kAxes[axis]).toRotationMatrix();
}

Matrix3d rotationFromEuler(XformOpKind order, const Vec3d& deg) {
  const auto& axes = info(order).axes;
  // Fixed-axis rotations compose right to left: the first axis is rightmost.
  return axisRotation(axes[2], deg[axes[2]]) * axisRotation(axes[1], deg[axes[1]]) *
         axisRotation(axes[0], deg[axes[0]]);
}

Vec3d eulerFromRotation(XformOpKind order, const Matrix3d& R) {
  // Tait-Bryan angles for R = R_k(c) * R_j(b) * R_i(a), where (i, j, k) is
  // the op's application order; the middle angle stays in [-90, 90] and the
  // others in [-180, 180], so a rotation about one axis reads back as that
  // axis' angle alone.
  const auto& axes = info(order).axes;
  const int i = axes[0], j = axes[1], k = axes[2];
  const double sign = ((j - i + 3) % 3 == 1) ? 1.0 : -1.0;  // cyclic order or not
  const double sb = std::clamp(-sign * R(k, i), -1.0, 1.0);
  double a, b = std::asin(sb), c;
  if (std::fabs(sb) < 1.0 - 1e-12) {
    a = std::atan2(sign * R(k, j), R(k, k));
    c = std::atan2(sign * R(j, i), R(i, i));
  } else {  // gimbal lock: only a + c (or a - c) is defined; put it all in c
    a = 0.0;
    c = std::atan2(-sign * R(i, j), R(j, j));
  }
  Vec3d out;
  out[i] = degrees(a);
  out[j] = degrees(b);
  out[k] = degrees(c);
  return out;
}

Matrix4d XformOp::matrix() const {
  Matrix4d m = Matrix4d::Identity();
  switch (kind) {
    case XformOpKind::Translate: m.block<3, 1>(0, 3) = value.get<Vec3d>(); break;
    case XformOpKind::Scale: m.block<3, 3>(0, 0) = value.get<Vec3d>().asDiagonal(); break;
    case XformOpKind::RotateX: m.block<3, 3>(0, 0) = axisRotation(0, value.get<double>()); break;
    case XformOpKind::RotateY: m.block<3, 3>(0, 0) = axisRotation(1, value.get<double>()); break;
    case XformOpKind::RotateZ: m.block<3, 3>(0, 0) = axisRotation(2, value.get<double>()); break;
    case XformOpKind::Orient: m.block<3, 3>(0, 0) = value.get<Quatd>().normalized().toRotationMatrix(); break;
    case XformOpKind::Transform: m = value.get<Matrix4d>(); break;
    default: m.block<3, 3>(0, 0) = rotationFromEuler(kind, value.get<Vec3d>()); break;
  }
  return m;
}

Matrix4d localMatrix(std::span<const XformOp> ops) {
  Matrix4d m = Matrix4d::Identity();
  for (const XformOp& op : ops) m = m * op.matrix();
  return m;
}

Decomposed decompose(const Matrix4d& m) {
  Decomposed d;
  d.translation = m.block<3, 1>(0, 3);
  Matrix3d linear = m.block<3, 3>(0, 0);
  // Gram-Schmidt on the columns keeps the rotation when there is shear.
  Vec3d x = linear.col(0), y = linear.col(1), z = linear.col(2);
  d.scale.x() = x.norm();
  x /= d.scale.x();
  y -= x * x.dot(y);
  d.scale.y() = y.norm();
  y /= d.scale.y();
  z -= x * x.dot(z) + y * y.dot(z);
  d.scale.z() = z.norm();
  z /= d.scale.z();
  d.rotation.col(0) = x;
  d.rotation.col(1) = y;
  d.rotation.col(2) = z;
  if (d.rotation.determinant() < 0) {  // a mirror: keep R proper, flip one scale
    d.rotation.col(2) = -d.rotation.col(2);
    d.scale.z() = -d.scale.z();
  }
  return d;
}

Matrix4d compose(const Vec3d& translation, const Matrix3d& rotation, const Vec3d& scale) {
  Matrix4d m = Matrix4d::Identity();
  m.block<3, 3>(0, 0) = rotation * scale.asDiagonal();
  m.block<3, 1>(0, 3) = translation;
  return m;
}

}  // namespace sdg
