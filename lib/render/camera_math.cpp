#include "render/camera_math.h"

namespace sdg {

Matrix4d viewMatrix(const RenderCamera& camera) { return camera.worldFromCamera.inverse(); }

Matrix4d projectionMatrix(const RenderCamera& c, int width, int height, const Eigen::Vector2d& jitter) {
  const double aspect = double(width) / double(height);
  const double n = c.nearClip, f = c.farClip;
  // NDC shift from the aperture offsets, plus the sub-pixel jitter.
  const double effectiveVertical = c.horizontalAperture / aspect;
  const double shiftX = 2.0 * c.horizontalApertureOffset / c.horizontalAperture + 2.0 * jitter.x() / width;
  const double shiftY = 2.0 * c.verticalApertureOffset / effectiveVertical - 2.0 * jitter.y() / height;
  Matrix4d p = Matrix4d::Zero();
  if (c.orthographic) {
    const double w = c.horizontalAperture / 10.0, h = w / aspect;
    p(0, 0) = 2.0 / w;
    p(1, 1) = 2.0 / h;
    p(2, 2) = -2.0 / (f - n);
    p(0, 3) = shiftX;
    p(1, 3) = shiftY;
    p(2, 3) = -(f + n) / (f - n);
    p(3, 3) = 1.0;
    return p;
  }
  const double sx = 2.0 * c.focalLength / c.horizontalAperture;
  p(0, 0) = sx;
  p(1, 1) = sx * aspect;
  p(0, 2) = -shiftX;  // divided by w = -z_cam, so this adds shiftX in NDC
  p(1, 2) = -shiftY;
  p(2, 2) = (f + n) / (n - f);
  p(2, 3) = 2.0 * f * n / (n - f);
  p(3, 2) = -1.0;
  return p;
}

Vec3d projectToPixel(const RenderCamera& camera, int width, int height, const Vec3d& world) {
  Eigen::Vector4d cam = viewMatrix(camera) * world.homogeneous();
  Eigen::Vector4d clip = projectionMatrix(camera, width, height) * cam;
  Vec3d ndc = clip.head<3>() / clip.w();
  return Vec3d((ndc.x() + 1.0) * 0.5 * width, (1.0 - ndc.y()) * 0.5 * height, -cam.z());
}

}  // namespace sdg
