#pragma once
// The lat-long (equirectangular) mapping of environment maps, shared by the
// rasterizer's shaders (written out again in GLSL), the pre-filtering of
// domes and the path tracer's dome sampling.
//
// The convention is OpenEXR's, which USD adopts for DomeLight textures, in
// the dome's own frame whose pole is +Y: the image's x runs from longitude
// +pi (left edge) to -pi (right edge), longitude 0 pointing along +Z and
// longitude +pi/2 along +X; its y runs from latitude +pi/2 (+Y, top row) to
// -pi/2 (bottom row). So the image's centre looks along +Z and a quarter of
// the way in from the left looks along +X.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace sdg {

inline constexpr float kLatLongPi = 3.14159265358979323846f;

// (u, v) in [0, 1]^2, u left to right, v top to bottom, for a unit direction.
inline Eigen::Vector2f latLongFromDirection(const Eigen::Vector3f& d) {
  const float longitude = std::atan2(d.x(), d.z());
  return {0.5f - longitude / (2.0f * kLatLongPi), std::acos(std::clamp(d.y(), -1.0f, 1.0f)) / kLatLongPi};
}

// The unit direction at (u, v); the inverse of latLongFromDirection.
inline Eigen::Vector3f directionFromLatLong(float u, float v) {
  const float longitude = (0.5f - u) * 2.0f * kLatLongPi;
  const float polar = v * kLatLongPi;  // from +Y
  const float s = std::sin(polar);
  return {s * std::sin(longitude), std::cos(polar), s * std::cos(longitude)};
}

}  // namespace sdg
