#include "render/raster/shadow_casters.h"

#include <cmath>

namespace sdg {

std::optional<int> flatAxis(const Eigen::AlignedBox3f& localBounds) {
  if (localBounds.isEmpty()) return std::nullopt;
  const Eigen::Vector3f size = localBounds.sizes();
  int axis = 0;
  size.minCoeff(&axis);
  if (!(size[axis] <= 1e-7f * size.maxCoeff())) return std::nullopt;
  return axis;
}

std::optional<FlatSurface> flatSurface(const Eigen::AlignedBox3f& localBounds, const float worldFromLocal[16]) {
  const std::optional<int> axis = flatAxis(localBounds);
  if (!axis) return std::nullopt;
  const Eigen::Matrix4d world = Eigen::Map<const Eigen::Matrix4f>(worldFromLocal).cast<double>();
  const Matrix3d linear = world.block<3, 3>(0, 0);
  if (std::fabs(linear.determinant()) < 1e-300) return std::nullopt;  // squashed flat: no plane to speak of
  FlatSurface s;
  s.point = (world * localBounds.center().cast<double>().homogeneous()).head<3>();
  s.normal = (linear.inverse().transpose() * Vec3d::Unit(*axis)).normalized();
  return s;
}

bool shadowsNothing(const FlatSurface& surface, const RenderLight& light,
                    const std::vector<Eigen::AlignedBox3d>& itemBounds, double tolerance) {
  // Turn the normal towards the light; a light in the plane (a distant one
  // grazing it, a lamp on it) lights both sides and decides nothing.
  double side;
  if (light.kind == LightKind::Distant) {
    side = -surface.normal.dot(light.direction.normalized());  // a cosine
    if (!(std::fabs(side) > 1e-9)) return false;
  } else if (light.kind == LightKind::Sphere) {
    side = surface.normal.dot(light.position - surface.point);  // a distance
    if (!(std::fabs(side) > tolerance)) return false;
  } else {
    return false;
  }
  const Vec3d n = side > 0 ? surface.normal : Vec3d(-surface.normal);
  const double offset = n.dot(surface.point);
  const Vec3d reach = n.cwiseAbs();
  for (const Eigen::AlignedBox3d& box : itemBounds) {
    if (box.isEmpty()) continue;
    // The box's lowest point along n: its centre less its half-size projected.
    const double lowest = n.dot(box.center()) - reach.dot(box.sizes() / 2) - offset;
    if (lowest < -tolerance) return false;
  }
  return true;
}

}  // namespace sdg
