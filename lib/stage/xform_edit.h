#pragma once
// Reading and writing a prim's location and rotation through its existing
// xform ops, as the Isaac Sim behaviors do (spec §2.2, §2.4). Where a prim
// lacks the op, sdgbehave inserts one where USD's common TRS order puts it
// (translate first, orient right after the leading translates) so it acts in
// the parent's frame; the behaviors remove ops they inserted when they stop.
#include <optional>

#include "stage/stage.h"

namespace sdg {

// Index of the first op named exactly xformOp:translate or xformOp:transform.
std::optional<size_t> findLocationOp(const Prim& prim);
// Index of the first rotate (any order, any suffix), orient or transform op.
std::optional<size_t> findRotationOp(const Prim& prim);

Vec3d opLocation(const XformOp& op);
void setOpLocation(XformOp& op, const Vec3d& location);
Matrix3d opRotation(const XformOp& op);
// Writes R into the op: a quaternion for orient, Euler angles decomposed for
// the op's axis order, one angle for single-axis rotates (lossy, as in
// Isaac Sim), the rotation part for a transform (translation and scale kept).
void setOpRotation(XformOp& op, const Matrix3d& R);

// Inserts an identity xformOp:translate before every other op; returns its index.
size_t insertTranslateOp(Prim& prim);
// Inserts an identity xformOp:orient after the leading translate ops.
size_t insertOrientOp(Prim& prim);
// Removes the op with that attribute name, if present.
void removeXformOp(Prim& prim, const std::string& attributeName);

// World rotation of a prim with scale and shear removed.
Matrix3d worldRotation(const Stage& stage, const Prim& prim);
Vec3d worldLocation(const Stage& stage, const Prim& prim);

}  // namespace sdg
