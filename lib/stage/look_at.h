#pragma once
// The rotation that points a prim's local -Z at a target with its +Y toward
// an up vector (USD's camera convention, gluLookAt's frame).
#include <cmath>
#include <optional>

#include "stage/math_types.h"

namespace sdg {

// nullopt when eye and target coincide (no direction to look in). When the
// direction is parallel to `up` (a target straight above or below), the first
// world axis that `up` has no component on stands in for it, as Isaac Sim's
// nudge does, but exactly: the view direction itself is never perturbed.
inline std::optional<Matrix3d> lookAtRotation(const Vec3d& eye, const Vec3d& target, const Vec3d& up) {
  constexpr double kEps = 1e-5;
  Vec3d dir = target - eye;
  if (dir.norm() == 0.0) return std::nullopt;
  Vec3d back = -dir.normalized();
  Vec3d upN = up.norm() > 0 ? Vec3d(up.normalized()) : Vec3d::UnitZ();
  Vec3d x = upN.cross(back);
  if (x.norm() < kEps) {
    Vec3d helper = std::fabs(upN.x()) < kEps ? Vec3d::UnitX() : std::fabs(upN.y()) < kEps ? Vec3d::UnitY() : Vec3d::UnitZ();
    x = helper.cross(back);
    if (x.norm() < kEps) x = Vec3d::UnitY().cross(back);
  }
  x.normalize();
  Vec3d y = back.cross(x);
  Matrix3d R;
  R.col(0) = x;
  R.col(1) = y;
  R.col(2) = back;
  return R;
}

}  // namespace sdg
