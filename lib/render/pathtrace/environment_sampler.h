#pragma once
// Importance sampling of a lat-long dome (an HDR environment map) for the
// path tracer's light sampling, with the density for multiple importance
// sampling.
//
// The texels form a piecewise-constant distribution over the sphere, each
// weighted by its luminance times its solid angle, (2 pi / width)
// (cos θtop - cos θbottom): that is sin θ integrated over the texel's row,
// exact even at the poles. Sampling takes a row from the marginal
// distribution, a column from that row's conditional one, both cumulative
// tables searched by bisection (as in Pharr, Jakob and Humphreys,
// "Physically Based Rendering", 3rd edition, 13.6.7), then a point uniform
// in solid angle inside the texel (uniform in longitude and in cos θ). So
// the density is constant over each texel: its probability over its solid
// angle, and a map whose light is in one texel is sampled with zero variance.
//
// Directions follow render/latlong.h, in the dome's frame (its pole is +Y);
// the caller turns them by the dome's transform. Where the map is black
// everywhere, the sampler falls back to the uniform sphere. Texels whose
// luminance is negative or not finite count as black.
#include <cstdint>
#include <vector>

#include "assets/image.h"
#include "stage/math_types.h"

namespace sdg {

struct EnvironmentSample {
  Vec3f direction;  // unit, in the dome's frame
  float pdf;        // per unit solid angle
};

class EnvironmentSampler {
 public:
  // Throws std::invalid_argument on an empty image or one with fewer
  // pixels than its size says.
  explicit EnvironmentSampler(const ImageRgbaF& image);

  // u in [0, 1)^2: u.y picks the row, u.x the column.
  EnvironmentSample sample(const Vec2f& u) const;
  // The density with which sample() returns `direction` (unit, dome frame).
  float pdf(const Vec3f& direction) const;

  // The tables, for the GPU tracer (render/pathtrace/gpu), which uploads them.
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  const std::vector<float>& rowCdf() const { return rowCdf_; }
  const std::vector<float>& columnCdf() const { return columnCdf_; }
  const std::vector<double>& rowCosines() const { return rowCosines_; }
  const std::vector<float>& texelSolidAngles() const { return texelSolidAngle_; }

 private:
  uint32_t width_, height_;
  std::vector<float> rowCdf_;           // height + 1 entries, 0 .. 1
  std::vector<float> columnCdf_;        // per row, width + 1 entries, 0 .. 1
  std::vector<double> rowCosines_;      // cos θ at the top of each row, and 1 more: the bottom
  std::vector<float> texelSolidAngle_;  // per row
};

// The texel (column, row) of a width x height lat-long image that holds
// `direction`: where a sample's radiance is read.
Vec2i latLongTexel(const Vec3f& direction, uint32_t width, uint32_t height);

}  // namespace sdg
