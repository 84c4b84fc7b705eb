// rotationRandomizer — gives prims random orientations.
//
// Exposed variables (exposedVar:rotationRandomizer:*):
//   range:minRotation  vector3d  (0, 0, 0)        degrees per axis
//   range:maxRotation  vector3d  (360, 360, 360)  degrees per axis
//   includeChildren    bool      true
//   interval           uint      0
//   seed               int       -1
//
// Per prim and apply: ax, ay, az drawn in that order, R = rotate about X by
// ax, then Y by ay, then Z by az (fixed axes; USD's rotateXYZ). A uniform draw
// of Euler angles, not a uniform rotation. R goes into the prim's first
// rotate/orient/transform op, decomposed for that op's axis order (single-axis
// ops keep only their own angle, as in Isaac Sim). A prim with none gets an
// xformOp:orient inserted after its translate, removed again on stop. On stop
// the original op values come back.
//
// Example:
//   behaviors:
//     rotationRandomizer: {range:minRotation: [0, 0, -45], range:maxRotation: [0, 0, 45]}
//
// Events: none (timeline driven).
#include <optional>

#include "behavior/interval_behavior.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "builtin_behaviors/rotation_ops.h"
#include "builtin_behaviors/spec_helpers.h"

namespace sdg {
namespace {

class RotationRandomizer final : public IntervalBehavior {
  void setup() override {
    minRotation_ = var<Vec3d>("range:minRotation");
    maxRotation_ = var<Vec3d>("range:maxRotation");
    if (isSetUp()) return;
    rng_ = makeRng(var<int32_t>("seed"));
    targets_.capture(stage(), selectPrims(var<bool>("includeChildren"), [](const Prim& p) {
      return p.typeInfo().xformable;
    }));
  }

  void apply() override {
    for (const RotationTarget& t : targets_.entries()) {
      double ax = rng_.uniform(minRotation_.x(), maxRotation_.x());
      double ay = rng_.uniform(minRotation_.y(), maxRotation_.y());
      double az = rng_.uniform(minRotation_.z(), maxRotation_.z());
      Matrix3d R = rotationFromEuler(XformOpKind::RotateXYZ, Vec3d(ax, ay, az));
      targets_.write(stage(), t, R);
    }
  }

  void restore() override { targets_.restore(stage()); }

  Rng rng_;
  RotationTargets targets_;
  Vec3d minRotation_, maxRotation_;
};

}  // namespace

BehaviorSpec rotationRandomizerSpec() {
  using namespace behaviors;
  BehaviorSpec spec;
  spec.name = "rotationRandomizer";
  spec.summary = "Gives prims random orientations from per-axis Euler angle ranges (degrees).";
  spec.variables = {
      variable("range:minRotation", Value::makeVector3d({0, 0, 0}), "Lower bound of the X, Y, Z angles (degrees)."),
      variable("range:maxRotation", Value::makeVector3d({360, 360, 360}), "Upper bound of the X, Y, Z angles (degrees)."),
      includeChildrenVariable(),
      intervalVariable(),
      seedVariable(),
  };
  spec.example = "rotationRandomizer: {range:minRotation: [0, 0, -45], range:maxRotation: [0, 0, 45]}";
  spec.validate = [](const Prim& prim, Diagnostics& diag) {
    behaviors::checkRange(prim, "rotationRandomizer", "range:minRotation", "range:maxRotation", diag);
  };
  return spec;
}

std::unique_ptr<Behavior> makeRotationRandomizer() { return std::make_unique<RotationRandomizer>(); }

}  // namespace sdg
