#include "stage/xform_edit.h"

#include "stage/stage.h"

namespace sdg {

std::optional<size_t> findLocationOp(const Prim& prim) {
  const auto& ops = prim.xformOps();
  for (size_t i = 0; i < ops.size(); ++i)
    if (ops[i].suffix.empty() && (ops[i].kind == XformOpKind::Translate || ops[i].kind == XformOpKind::Transform))
      return i;
  return std::nullopt;
}

std::optional<size_t> findRotationOp(const Prim& prim) {
  const auto& ops = prim.xformOps();
  for (size_t i = 0; i < ops.size(); ++i)
    if (isRotateKind(ops[i].kind) || ops[i].kind == XformOpKind::Orient || ops[i].kind == XformOpKind::Transform)
      return i;
  return std::nullopt;
}

Vec3d opLocation(const XformOp& op) {
  if (op.kind == XformOpKind::Transform) return op.value.get<Matrix4d>().block<3, 1>(0, 3);
  return op.value.get<Vec3d>();
}

void setOpLocation(XformOp& op, const Vec3d& location) {
  if (op.kind == XformOpKind::Transform) op.value.get<Matrix4d>().block<3, 1>(0, 3) = location;
  else op.value.get<Vec3d>() = location;
}

Matrix3d opRotation(const XformOp& op) {
  if (op.kind == XformOpKind::Transform) return decompose(op.value.get<Matrix4d>()).rotation;
  return op.matrix().block<3, 3>(0, 0);
}

void setOpRotation(XformOp& op, const Matrix3d& R) {
  switch (op.kind) {
    case XformOpKind::Orient: op.value.get<Quatd>() = Quatd(R).normalized(); break;
    case XformOpKind::RotateX: op.value.get<double>() = eulerFromRotation(XformOpKind::RotateXYZ, R).x(); break;
    case XformOpKind::RotateY: op.value.get<double>() = eulerFromRotation(XformOpKind::RotateXYZ, R).y(); break;
    case XformOpKind::RotateZ: op.value.get<double>() = eulerFromRotation(XformOpKind::RotateXYZ, R).z(); break;
    case XformOpKind::Transform: {
      Decomposed d = decompose(op.value.get<Matrix4d>());
      op.value.get<Matrix4d>() = compose(d.translation, R, d.scale);
      break;
    }
    default: op.value.get<Vec3d>() = eulerFromRotation(op.kind, R); break;
  }
}

size_t insertTranslateOp(Prim& prim) {
  XformOp op;
  op.kind = XformOpKind::Translate;
  op.value = Value::makeDouble3(Vec3d::Zero());
  prim.xformOps().insert(prim.xformOps().begin(), op);
  return 0;
}

size_t insertOrientOp(Prim& prim) {
  auto& ops = prim.xformOps();
  size_t at = 0;
  while (at < ops.size() && ops[at].kind == XformOpKind::Translate) ++at;
  XformOp op;
  op.kind = XformOpKind::Orient;
  op.value = Value::makeQuatd(Quatd::Identity());
  ops.insert(ops.begin() + static_cast<std::ptrdiff_t>(at), op);
  return at;
}

void removeXformOp(Prim& prim, const std::string& attributeName) {
  std::erase_if(prim.xformOps(), [&](const XformOp& op) { return op.attributeName() == attributeName; });
}

Matrix3d worldRotation(const Stage& stage, const Prim& prim) { return decompose(stage.worldMatrix(prim)).rotation; }

Vec3d worldLocation(const Stage& stage, const Prim& prim) { return stage.worldMatrix(prim).block<3, 1>(0, 3); }

}  // namespace sdg
