#include "builtin_behaviors/rotation_ops.h"

#include <optional>

#include "stage/xform_edit.h"

namespace sdg {

void RotationTargets::capture(Stage&, const std::vector<Prim*>& prims) {
  entries_.clear();
  for (Prim* p : prims) {
    RotationTarget t;
    t.path = p->path();
    std::optional<size_t> index = findRotationOp(*p);
    if (!index) {
      index = insertOrientOp(*p);
      t.inserted = true;
    }
    const XformOp& op = p->xformOps()[*index];
    t.opName = op.attributeName();
    t.initialValue = op.value;
    entries_.push_back(std::move(t));
  }
}

void RotationTargets::write(Stage& stage, const RotationTarget& target, const Matrix3d& localRotation) const {
  if (Prim* p = stage.find(target.path))
    if (XformOp* op = p->findXformOp(target.opName)) setOpRotation(*op, localRotation);
}

void RotationTargets::restore(Stage& stage) {
  for (const RotationTarget& t : entries_) {
    Prim* p = stage.find(t.path);
    if (!p) continue;
    if (t.inserted) removeXformOp(*p, t.opName);
    else if (XformOp* op = p->findXformOp(t.opName)) op->value = t.initialValue;
  }
  entries_.clear();
}

}  // namespace sdg
