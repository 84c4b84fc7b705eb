// locationRandomizer — moves prims to random positions inside a box.
//
// Exposed variables (exposedVar:locationRandomizer:*):
//   range:minPosition       vector3d  (-1, -1, -1)  lower bound of the random offset (scene units)
//   range:maxPosition       vector3d  ( 1,  1,  1)  upper bound
//   frame:useRelativeFrame  bool      true          keep the initial offset (see below)
//   frame:targetPrimPath    string    ""            optional anchor prim
//   includeChildren         bool      true          also move every Xformable descendant
//   interval                uint      0             apply every N updates (0 = every update)
//   seed                    int       -1            -1 = from the run seed; >= 0 fixes the stream
//
// Per prim and apply, o = (U(minX,maxX), U(minY,maxY), U(minZ,maxZ)) drawn x, y, z, then:
//   target,  relative:  world(target) + offset_at_play + o
//   target,  absolute:  world(target) + o
//   none,    relative:  initial local translate + o
//   none,    absolute:  o
// The value goes into the first xformOp:translate (or the translation of
// xformOp:transform); a prim with neither gets a translate op inserted first
// in its op order, removed again on stop. With a target the formulas are
// world positions and sdgbehave converts them into the prim's parent frame
// (Isaac Sim writes them into the local op, exact only under an identity
// parent). On stop every prim gets its initial value back.
//
// Example:
//   behaviors:
//     locationRandomizer: {interval: 3, range:minPosition: [-0.2, -0.2, -0.2], range:maxPosition: [0.2, 0.2, 0.2]}
//
// Events: none (timeline driven).
#include <optional>

#include "behavior/interval_behavior.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "builtin_behaviors/spec_helpers.h"
#include "stage/xform_edit.h"

namespace sdg {
namespace {

class LocationRandomizer final : public IntervalBehavior {
  struct Entry {
    std::string path;
    std::string opName;       // the op written (after insertion if needed)
    bool inserted = false;
    Value initialValue;       // the op's value at setup, restored on stop
    Vec3d initialLocal;
    Vec3d targetOffset;       // world offset from the target at setup
  };

  void setup() override {
    minPosition_ = var<Vec3d>("range:minPosition");
    maxPosition_ = var<Vec3d>("range:maxPosition");
    relative_ = var<bool>("frame:useRelativeFrame");
    targetPath_ = xformableTarget("frame:targetPrimPath", "using no target");
    if (isSetUp()) return;
    rng_ = makeRng(var<int32_t>("seed"));
    entries_.clear();
    for (Prim* p : selectPrims(var<bool>("includeChildren"), [](const Prim& q) { return q.typeInfo().xformable; })) {
      Entry e;
      e.path = p->path();
      std::optional<size_t> index = findLocationOp(*p);
      if (!index) {
        index = insertTranslateOp(*p);
        e.inserted = true;
      }
      const XformOp& op = p->xformOps()[*index];
      e.opName = op.attributeName();
      e.initialValue = op.value;
      e.initialLocal = opLocation(op);
      if (!targetPath_.empty())
        e.targetOffset = worldLocation(stage(), *p) - worldLocation(stage(), *stage().find(targetPath_));
      entries_.push_back(std::move(e));
    }
  }

  void apply() override {
    const Prim* target = targetPath_.empty() ? nullptr : stage().find(targetPath_);
    for (const Entry& e : entries_) {
      Vec3d o;
      for (int axis = 0; axis < 3; ++axis) o[axis] = rng_.uniform(minPosition_[axis], maxPosition_[axis]);
      Prim& p = *stage().find(e.path);
      XformOp& op = *p.findXformOp(e.opName);
      if (!target) {
        setOpLocation(op, relative_ ? Vec3d(e.initialLocal + o) : o);
        continue;
      }
      Vec3d world = worldLocation(stage(), *target) + (relative_ ? e.targetOffset : Vec3d::Zero()) + o;
      // Into the parent's frame: the op holds the prim's origin in parent space.
      Matrix4d parentWorld = p.parent()->isPseudoRoot() ? Matrix4d::Identity() : stage().worldMatrix(*p.parent());
      setOpLocation(op, (parentWorld.inverse() * world.homogeneous()).head<3>());
    }
  }

  void restore() override {
    for (const Entry& e : entries_) {
      Prim* p = stage().find(e.path);
      if (!p) continue;
      if (e.inserted) removeXformOp(*p, e.opName);
      else if (XformOp* op = p->findXformOp(e.opName)) op->value = e.initialValue;
    }
    entries_.clear();
  }

  Rng rng_;
  std::vector<Entry> entries_;
  Vec3d minPosition_, maxPosition_;
  bool relative_ = true;
  std::string targetPath_;
};

}  // namespace

BehaviorSpec locationRandomizerSpec() {
  using namespace behaviors;
  BehaviorSpec spec;
  spec.name = "locationRandomizer";
  spec.summary = "Moves prims to random positions within a box, optionally relative to a target prim.";
  spec.variables = {
      variable("range:minPosition", Value::makeVector3d({-1, -1, -1}), "Lower bound of the random offset per axis."),
      variable("range:maxPosition", Value::makeVector3d({1, 1, 1}), "Upper bound of the random offset per axis."),
      variable("frame:useRelativeFrame", Value::makeBool(true),
               "Keep the initial position (or the initial offset from the target) and add the random offset."),
      primPathVariable("frame:targetPrimPath", "Optional prim whose world position anchors the random offset."),
      includeChildrenVariable(),
      intervalVariable(),
      seedVariable(),
  };
  spec.example = "locationRandomizer: {interval: 2, range:minPosition: [-1.25, -1.25, 0], range:maxPosition: [1.25, 1.25, 0]}";
  spec.validate = [](const Prim& prim, Diagnostics& diag) {
    behaviors::checkRange(prim, "locationRandomizer", "range:minPosition", "range:maxPosition", diag);
  };
  return spec;
}

std::unique_ptr<Behavior> makeLocationRandomizer() { return std::make_unique<LocationRandomizer>(); }

}  // namespace sdg
