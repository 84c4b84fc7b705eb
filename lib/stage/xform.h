#pragma once
// USD transform ops. A prim's local matrix is the product of its ops in
// xformOpOrder: with column vectors, M = op[0] * op[1] * ... * op[n-1], so the
// last op applies first to a point (USD's "translate, rotate, scale" order
// scales, then rotates, then translates).
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "stage/value.h"

namespace sdg {

enum class XformOpKind {
  Translate, Scale,
  RotateX, RotateY, RotateZ,
  RotateXYZ, RotateXZY, RotateYXZ, RotateYZX, RotateZXY, RotateZYX,
  Orient, Transform,
};

std::span<const XformOpKind> allXformOpKinds();
// "translate", "rotateXYZ", "orient", ...
std::string_view xformOpKindName(XformOpKind kind);
std::optional<XformOpKind> xformOpKindFromName(std::string_view name);
// The value type an op of this kind holds (all double precision here).
ValueType xformOpValueType(XformOpKind kind);
bool isRotateKind(XformOpKind kind);        // rotateX..rotateZYX
bool isThreeAxisRotate(XformOpKind kind);   // rotateXYZ..rotateZYX

struct XformOp {
  XformOpKind kind = XformOpKind::Translate;
  std::string suffix;  // "pivot" in "xformOp:translate:pivot"; usually empty
  Value value;

  // "xformOp:translate" or "xformOp:translate:pivot".
  std::string attributeName() const;
  Matrix4d matrix() const;
  bool operator==(const XformOp&) const = default;
};

// Parses "xformOp:rotateXYZ[:suffix]"; nullopt when not an op name.
std::optional<XformOp> parseXformOpName(std::string_view attributeName);

Matrix4d localMatrix(std::span<const XformOp> ops);

// Rotation for Euler angles in degrees (x, y, z components) applied in the
// order of a three-axis rotate kind, about fixed parent axes.
Matrix3d rotationFromEuler(XformOpKind order, const Vec3d& degreesXYZ);
// The inverse: angles (x, y, z) in degrees that reproduce R under `order`.
Vec3d eulerFromRotation(XformOpKind order, const Matrix3d& R);
Matrix3d axisRotation(int axis, double degrees);

// Splits a matrix into translation, rotation and (positive) scale, dropping
// shear; used to replace one of the parts of a transform op.
struct Decomposed {
  Vec3d translation;
  Matrix3d rotation;
  Vec3d scale;
};
Decomposed decompose(const Matrix4d& m);
Matrix4d compose(const Vec3d& translation, const Matrix3d& rotation, const Vec3d& scale);

}  // namespace sdg
