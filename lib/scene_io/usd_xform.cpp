// USD transform ops and layer units as stage xform ops. The stage composes
// ops in xformOpOrder exactly as USD does (stage/xform.h), so most ops map
// one to one; `!invert!` and `!resetXformStack!` have no stage form and are
// baked into transform ops when the stage is imported.
#include <cmath>

#include "scene_io/usd_import.h"
#include "scene_io/usd_import_internal.h"

namespace sdg::usd_map {
namespace {

constexpr std::string_view kInvert = "!invert!";
constexpr std::string_view kReset = "!resetXformStack!";

XformOp transformOp(const std::string& suffix, const Matrix4d& m) {
  XformOp op;
  op.kind = XformOpKind::Transform;
  op.suffix = suffix;
  op.value = Value::makeMatrix4d(m);
  return op;
}

std::string sanitized(std::string s) {
  for (char& c : s)
    if (c == ':') c = '_';
  return s;
}

}  // namespace

std::vector<XformOp> xformOpsOf(const usd::ComposedPrim& prim, const Matrix4d& parentWorld, Diagnostics& diag) {
  std::vector<XformOp> ops;
  const usd::ComposedProperty* order = prim.property("xformOpOrder");
  if (!order || order->value.empty()) return ops;
  if (!usd::isText(order->value.kind)) {
    diag.error(order->loc, prim.path + ".xformOpOrder: expected token[], found " + std::string(usd::kindName(order->value.kind)));
    return ops;
  }
  const std::vector<std::string>& names = order->value.strings;
  for (size_t i = 0; i < names.size(); ++i) {
    std::string_view name = names[i];
    if (name == kReset) {
      // Ignore the parent's transform: undo it here (baked at import).
      ops.clear();
      ops.push_back(transformOp("resetXformStack", parentWorld.inverse()));
      continue;
    }
    const bool invert = name.substr(0, kInvert.size()) == kInvert;
    if (invert) name.remove_prefix(kInvert.size());
    std::optional<XformOp> op = parseXformOpName(name);
    if (!op) {
      diag.error(order->loc, prim.path + ".xformOpOrder: " + std::string(names[i]) +
                                 " is not a transform op (xformOp:translate, rotateXYZ, orient, scale, transform, ...)");
      continue;
    }
    const usd::ComposedProperty* attr = prim.property(std::string(name));
    if (!attr || attr->value.empty()) {
      diag.error(order->loc, prim.path + ".xformOpOrder: names " + std::string(name) + ", which has no value");
      continue;
    }
    std::optional<Value> v = toStageValue(attr->value, xformOpValueType(op->kind));
    if (!v) {
      diag.error(attr->loc, prim.path + "." + std::string(name) + ": expected " +
                                std::string(valueTypeName(xformOpValueType(op->kind))) + " (any precision), found " +
                                attr->typeName);
      continue;
    }
    op->value = *v;
    if (op->kind == XformOpKind::Orient) {
      Quatd q = op->value.get<Quatd>();
      if (q.norm() > 0) q.normalize();
      op->value = Value::makeQuatd(q);
    }
    if (invert) ops.push_back(transformOp("inverse_" + sanitized(std::string(name.substr(8))), op->matrix().inverse()));
    else ops.push_back(*op);
  }
  return ops;
}

double unitsScale(const usd::LayerUnits& from, const usd::LayerUnits& to) { return from.metersPerUnit / to.metersPerUnit; }

std::vector<XformOp> unitsOps(const usd::LayerUnits& from, const usd::LayerUnits& to) {
  std::vector<XformOp> ops;
  if (from.upAxis != to.upAxis) {
    // Y up into Z up turns +Y onto +Z (a quarter turn about X); back the other way.
    XformOp r;
    r.kind = XformOpKind::RotateX;
    r.suffix = std::string(kUnitsResolveSuffix);
    r.value = Value::makeDouble(from.upAxis == "Y" ? 90.0 : -90.0);
    ops.push_back(r);
  }
  const double s = unitsScale(from, to);
  if (s != 1.0) {
    XformOp op;
    op.kind = XformOpKind::Scale;
    op.suffix = std::string(kUnitsResolveSuffix);
    op.value = Value::makeDouble3(Vec3d(s, s, s));
    ops.push_back(op);
  }
  return ops;
}

}  // namespace sdg::usd_map
