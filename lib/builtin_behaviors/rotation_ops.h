#pragma once
// The rotation bookkeeping rotationRandomizer and lookAtBehavior share: which
// op of each prim receives the rotation, its value before play, and whether
// the behavior inserted it (so stop can undo exactly).
#include <string>
#include <vector>

#include "stage/stage.h"

namespace sdg {

struct RotationTarget {
  std::string path;
  std::string opName;
  bool inserted = false;
  Value initialValue;
};

class RotationTargets {
 public:
  // Finds (or inserts) the rotation op of each prim and remembers its value.
  void capture(Stage& stage, const std::vector<Prim*>& prims);
  const std::vector<RotationTarget>& entries() const { return entries_; }
  // Writes a rotation (in the prim's local frame) into the target's op.
  void write(Stage& stage, const RotationTarget& target, const Matrix3d& localRotation) const;
  // Puts every op back as captured and forgets the prims.
  void restore(Stage& stage);

 private:
  std::vector<RotationTarget> entries_;
};

}  // namespace sdg
