#include "render/raster/shadow_frusta.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "render/camera_math.h"

namespace sdg {

namespace {

std::array<Vec3d, 8> corners(const Eigen::AlignedBox3d& box) {
  std::array<Vec3d, 8> c;
  for (int i = 0; i < 8; ++i) c[size_t(i)] = box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(i));
  return c;
}

// A right-handed view looking along `forward` from `eye`.
Matrix4d lookAlong(const Vec3d& eye, const Vec3d& forward) {
  Vec3d up = std::fabs(forward.z()) < 0.9 ? Vec3d::UnitZ() : Vec3d::UnitX();
  Vec3d right = forward.cross(up).normalized();
  up = right.cross(forward);
  Matrix4d view = Matrix4d::Identity();
  view.block<1, 3>(0, 0) = right.transpose();
  view.block<1, 3>(1, 0) = up.transpose();
  view.block<1, 3>(2, 0) = -forward.transpose();
  view.block<3, 1>(0, 3) = -view.block<3, 3>(0, 0) * eye;
  return view;
}

Matrix4d orthographic(double l, double r, double b, double t, double n, double f) {
  Matrix4d p = Matrix4d::Identity();
  p(0, 0) = 2.0 / (r - l);
  p(0, 3) = -(r + l) / (r - l);
  p(1, 1) = 2.0 / (t - b);
  p(1, 3) = -(t + b) / (t - b);
  p(2, 2) = -2.0 / (f - n);
  p(2, 3) = -(f + n) / (f - n);
  return p;
}

Matrix4d perspective(double halfAngle, double n, double f) {
  Matrix4d p = Matrix4d::Zero();
  p(0, 0) = p(1, 1) = 1.0 / std::tan(halfAngle);
  p(2, 2) = (f + n) / (n - f);
  p(2, 3) = 2 * f * n / (n - f);
  p(3, 2) = -1.0;
  return p;
}

// Widest a sphere light's single map may open (half angle); points outside
// it are lit unshadowed.
constexpr double kMaxHalfAngle = 75.0 * M_PI / 180.0;

}  // namespace

Eigen::AlignedBox3d visibleRegion(const RenderCamera& camera, int width, int height, const Eigen::AlignedBox3d& scene) {
  if (scene.isEmpty()) return scene;
  const Matrix4d view = viewMatrix(camera);
  // The far plane no deeper than the scene's farthest corner.
  double deepest = 0;
  for (const Vec3d& c : corners(scene)) deepest = std::max(deepest, -(view * c.homogeneous()).z());
  if (deepest <= camera.nearClip) return scene;  // everything is behind the camera or before the near plane
  RenderCamera cut = camera;
  cut.farClip = float(std::min(double(camera.farClip), deepest * 1.001));
  const Matrix4d worldFromClip = (projectionMatrix(cut, width, height) * view).inverse();
  Eigen::AlignedBox3d frustum;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector4d ndc((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0, 1.0);
    const Eigen::Vector4d world = worldFromClip * ndc;
    frustum.extend(world.head<3>() / world.w());
  }
  Eigen::AlignedBox3d seen = frustum.intersection(scene);
  return seen.isEmpty() ? scene : seen;
}

Matrix4d shadowViewProjection(const RenderLight& light, const Eigen::AlignedBox3d& receivers,
                              const Eigen::AlignedBox3d& scene) {
  // A little slack around the receivers, so the filter taps at their edge
  // still read texels drawn this frame.
  Eigen::AlignedBox3d padded = receivers;
  const Vec3d slack = Vec3d::Constant(std::max(receivers.diagonal().norm() * 0.02, 1e-3));
  padded.min() -= slack;
  padded.max() += slack;
  if (light.kind == LightKind::Distant) {
    // Parallel rays: only casters over the receivers' footprint matter, but
    // at any height along the light, so depth spans the whole scene.
    const Vec3d forward = light.direction.normalized();
    const Matrix4d view = lookAlong(padded.center(), forward);
    Eigen::AlignedBox3d footprint, depth;
    for (const Vec3d& c : corners(padded)) footprint.extend((view * c.homogeneous()).head<3>());
    for (const Vec3d& c : corners(scene)) depth.extend((view * c.homogeneous()).head<3>());
    depth.extend(footprint);
    const double n = -depth.max().z() - slack.x(), f = -depth.min().z() + slack.x();
    return orthographic(footprint.min().x(), footprint.max().x(), footprint.min().y(), footprint.max().y(), n, f) * view;
  }
  // A sphere light: one perspective map from the light toward the receivers
  // (straight down when the light is among them), opening no wider than the
  // cap.
  const Vec3d toCentre = padded.center() - light.position;
  const bool inside = padded.contains(light.position) || toCentre.norm() < 1e-6;
  const Vec3d forward = inside ? Vec3d(-Vec3d::UnitZ()) : Vec3d(toCentre.normalized());
  double halfAngle = inside ? kMaxHalfAngle : 0.0;
  double farthest = 0;
  for (const Vec3d& c : corners(padded)) {
    const Vec3d toCorner = c - light.position;
    farthest = std::max(farthest, toCorner.norm());
    if (!inside) halfAngle = std::max(halfAngle, std::acos(std::clamp(toCorner.normalized().dot(forward), -1.0, 1.0)));
  }
  halfAngle = std::clamp(halfAngle, 1e-3, kMaxHalfAngle);
  const double f = std::max(farthest * 1.01, 2e-3), n = std::max(0.005 * f, 1e-3);
  return perspective(halfAngle, n, f) * lookAlong(light.position, forward);
}

}  // namespace sdg
