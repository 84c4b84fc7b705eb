// lookAtBehavior — keeps prims (usually a camera) aimed at a point or a prim.
//
// Exposed variables (exposedVar:lookAtBehavior:*):
//   targetLocation   vector3d  (0, 0, 0)  world point to look at
//   targetPrimPath   string    ""         a prim whose world position wins over targetLocation
//   upAxis           vector3d  (0, 0, 1)  world up; +Z keeps the horizon level
//   includeChildren  bool      true       aim every Xformable descendant too (each independently)
//   interval         uint      0
//
// Per prim and apply: the prim's local -Z points at the target and its +Y
// lies in the plane of the view direction and upAxis. No random draws. The
// rotation goes into the prim's rotation op (inserting an xformOp:orient when
// there is none, removed on stop). sdgbehave compensates the parent's world
// rotation so the aim is exact under rotated parents (Isaac Sim writes the
// world rotation into the local op). A target straight above or below uses a
// substitute up axis (see stage/look_at.h). An invalid targetPrimPath warns
// with the path and falls back to targetLocation.
//
// Example:
//   behaviors:
//     lookAtBehavior: {targetPrimPath: /Root/Target}
//
// Events: none (timeline driven).
#include "behavior/interval_behavior.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "builtin_behaviors/rotation_ops.h"
#include "builtin_behaviors/spec_helpers.h"
#include "stage/look_at.h"
#include "stage/xform_edit.h"

namespace sdg {
namespace {

class LookAtBehavior final : public IntervalBehavior {
  void setup() override {
    targetLocation_ = var<Vec3d>("targetLocation");
    upAxis_ = var<Vec3d>("upAxis");
    targetPath_ = xformableTarget("targetPrimPath", "using targetLocation");
    if (isSetUp()) return;
    targets_.capture(stage(), selectPrims(var<bool>("includeChildren"), [](const Prim& p) {
      return p.typeInfo().xformable;
    }));
  }

  void apply() override {
    const Prim* targetPrim = targetPath_.empty() ? nullptr : stage().find(targetPath_);
    Vec3d target = targetPrim ? worldLocation(stage(), *targetPrim) : targetLocation_;
    for (const RotationTarget& t : targets_.entries()) {
      Prim& p = *stage().find(t.path);
      std::optional<Matrix3d> world = lookAtRotation(worldLocation(stage(), p), target, upAxis_);
      if (!world) continue;  // standing on the target: keep the current aim
      Matrix3d parent = p.parent()->isPseudoRoot() ? Matrix3d::Identity() : worldRotation(stage(), *p.parent());
      targets_.write(stage(), t, parent.transpose() * *world);
    }
  }

  void restore() override { targets_.restore(stage()); }

  RotationTargets targets_;
  Vec3d targetLocation_, upAxis_;
  std::string targetPath_;
};

}  // namespace

BehaviorSpec lookAtBehaviorSpec() {
  using namespace behaviors;
  BehaviorSpec spec;
  spec.name = "lookAtBehavior";
  spec.summary = "Keeps prims aimed (local -Z) at a world point or at a prim, with +Y toward an up axis.";
  spec.variables = {
      variable("targetLocation", Value::makeVector3d({0, 0, 0}), "World point to look at."),
      primPathVariable("targetPrimPath", "Prim to look at; when set it wins over targetLocation."),
      variable("upAxis", Value::makeVector3d({0, 0, 1}), "World up direction for the view."),
      includeChildrenVariable(),
      intervalVariable(),
  };
  spec.example = "lookAtBehavior: {targetPrimPath: /Root/Target}";
  return spec;
}

std::unique_ptr<Behavior> makeLookAtBehavior() { return std::make_unique<LookAtBehavior>(); }

}  // namespace sdg
