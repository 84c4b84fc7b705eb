#pragma once
// What a USD asset without a camera or lights needs to be rendered at all:
// most real assets (a teapot, a chair) carry neither. The framing is fixed
// and documented in docs/usd.md (Defaults a USD stage does not say).
#include <string>

#include "scene_io/scene.h"

namespace sdg {

// The horizontal field of view of the framing camera, and the direction
// (from the stage's centre, Z up) it looks from: front (-Y), a little to
// the right (+X) and above, so that an upright asset shows three faces.
inline constexpr double kDefaultCameraFovDegrees = 60.0;

// The world bounds of the stage's geometry (gprims and inline meshes;
// mesh files, which a USD stage has none of, are not opened), as a sphere.
struct BoundingSphere {
  Vec3d centre = Vec3d::Zero();
  double radius = 0;  // 0: the stage has no geometry
};
BoundingSphere stageBoundingSphere(const Stage& stage);

// Adds /DefaultCamera framing the bounding sphere at the render resolution's
// aspect when the stage has no Camera, and /DefaultLight (a DistantLight)
// plus /DefaultDome (a uniform DomeLight) when it has no light. Returns the
// paths added, in that order.
std::vector<std::string> addDefaultCameraAndLights(Scene& scene);

}  // namespace sdg
