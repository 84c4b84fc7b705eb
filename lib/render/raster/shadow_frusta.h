#pragma once
// Where each shadow map looks. A map spread over the whole scene wastes
// almost all of its texels on a 30 m floor the camera never sees; fitted to
// the part of the scene inside the camera's frustum, a map of the output's
// own size gives sharper shadows than a far larger one spread wide.
#include <Eigen/Geometry>

#include "render/render_list.h"

namespace sdg {

// The camera's frustum, cut off where the scene ends, intersected with the
// scene's bounds: the only surfaces whose shadows can show. The whole scene
// when the camera sees none of it.
Eigen::AlignedBox3d visibleRegion(const RenderCamera& camera, int width, int height, const Eigen::AlignedBox3d& scene);

// A distant or sphere light's view-projection: its map covers every point
// of `receivers`, and every point of `scene` that could shadow one of them
// lies between its near and far planes.
Matrix4d shadowViewProjection(const RenderLight& light, const Eigen::AlignedBox3d& receivers,
                              const Eigen::AlignedBox3d& scene);

}  // namespace sdg
