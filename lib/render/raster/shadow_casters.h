#pragma once
// Which meshes a light's shadow map can leave out. Nearly every synthetic
// scene stands on a ground plane, and it fills every shadow map: drawing it
// costs llvmpipe a depth test per texel of every map, about a millisecond a
// frame for three lights at 512 x 512, yet it shadows nothing when the rest
// of the scene lies on the light's side of it. A flat item cannot shadow
// itself either, so leaving it out changes no lit-or-shadowed test, but for
// acne the bias might have let the plane cast on itself.
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "render/render_list.h"

namespace sdg {

// An item that lies entirely in one plane: a point on it and its normal.
struct FlatSurface {
  Vec3d point = Vec3d::Zero();
  Vec3d normal = Vec3d::UnitZ();
};

// The local axis along which a mesh's bounds have no thickness; nothing for
// a mesh with volume.
std::optional<int> flatAxis(const Eigen::AlignedBox3f& localBounds);

// The plane of a mesh whose local bounds have no thickness along some axis,
// placed by `worldFromLocal` (column-major 4 x 4, as an instance record has
// it); nothing for a mesh with volume.
std::optional<FlatSurface> flatSurface(const Eigen::AlignedBox3f& localBounds, const float worldFromLocal[16]);

// Whether `surface` can be left out of `light`'s shadow map: every box of
// `itemBounds` (the world bounds of every item, the surface's own included)
// lies on the light's side of its plane, reaching behind it by no more than
// `tolerance` (items resting on the plane touch it). A light in the plane,
// or one that is neither distant nor a sphere, never lets it.
bool shadowsNothing(const FlatSurface& surface, const RenderLight& light,
                    const std::vector<Eigen::AlignedBox3d>& itemBounds, double tolerance);

}  // namespace sdg
