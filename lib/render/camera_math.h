#pragma once
// Camera matrices from USD camera attributes, shared by the renderer and the
// camera_params annotator. As Replicator does, the horizontal aperture and
// the image's aspect ratio set the field of view (the vertical aperture is
// not used); apertures and the focal length share one unit (usually mm). An
// orthographic camera's aperture is in tenths of a scene unit, as in USD.
#include "render/render_list.h"

namespace sdg {

// world -> camera (the inverse of the camera's scale-free world matrix).
Matrix4d viewMatrix(const RenderCamera& camera);
// OpenGL clip-space projection with the clipping range; `jitter` shifts the
// image by a fraction of a pixel (x right, y down).
Matrix4d projectionMatrix(const RenderCamera& camera, int width, int height, const Eigen::Vector2d& jitter = {0, 0});
// Where a world point lands in pixel coordinates (x right, y down, pixel
// centres at .5); the third component is the depth along the optical axis.
Vec3d projectToPixel(const RenderCamera& camera, int width, int height, const Vec3d& world);

}  // namespace sdg
