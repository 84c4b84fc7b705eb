#include "render/pathtrace/environment_sampler.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/latlong.h"

namespace sdg {
namespace {

constexpr double kPi = 3.14159265358979323846;

double luminance(const float* rgba) {
  const double y = 0.2126 * rgba[0] + 0.7152 * rgba[1] + 0.0722 * rgba[2];
  return y > 0.0 && std::isfinite(y) ? y : 0.0;
}

// Appends the cumulative table of weights[0 .. count): count + 1 entries
// from 0 to exactly 1. All-zero weights give a uniform table (such a row
// has probability 0 and is never drawn; the table only has to be valid).
void appendCdf(const double* weights, size_t count, std::vector<float>& cdf) {
  double total = 0;
  for (size_t i = 0; i < count; ++i) total += weights[i];
  double running = 0;
  cdf.push_back(0.0f);
  for (size_t i = 0; i < count; ++i) {
    running += total > 0.0 ? weights[i] : 1.0;
    cdf.push_back(static_cast<float>(running / (total > 0.0 ? total : double(count))));
  }
  cdf.back() = 1.0f;
}

struct CdfPick {
  uint32_t cell;
  float offset;  // where u falls inside the cell, [0, 1)
};

// The cell with cdf[cell] <= u < cdf[cell + 1]: never an empty one, since
// the bisection looks for the first entry above u.
CdfPick pickCell(const float* cdf, uint32_t count, float u) {
  const float* above = std::upper_bound(cdf, cdf + count + 1, u);
  const uint32_t cell = std::min(static_cast<uint32_t>(std::max<std::ptrdiff_t>(above - cdf - 1, 0)), count - 1);
  const float width = cdf[cell + 1] - cdf[cell];
  const float offset = width > 0.0f ? (u - cdf[cell]) / width : 0.0f;
  return {cell, std::clamp(offset, 0.0f, 0x1.fffffep-1f)};
}

}  // namespace

Vec2i latLongTexel(const Vec3f& direction, uint32_t width, uint32_t height) {
  const Vec2f uv = latLongFromDirection(direction);
  return {std::clamp(static_cast<int>(uv.x() * float(width)), 0, int(width) - 1),
          std::clamp(static_cast<int>(uv.y() * float(height)), 0, int(height) - 1)};
}

EnvironmentSampler::EnvironmentSampler(const ImageRgbaF& image) : width_(image.width), height_(image.height) {
  if (width_ == 0 || height_ == 0 || image.pixels.size() < size_t(width_) * height_ * 4)
    throw std::invalid_argument("EnvironmentSampler: the image is empty or smaller than its size");
  // Row j spans polar angles [j, j + 1] pi / height; cos a - cos b is
  // written as 2 sin((a + b) / 2) sin((b - a) / 2), exact near the poles.
  rowCosines_.resize(height_ + 1);
  texelSolidAngle_.resize(height_);
  std::vector<double> rowSolidAngle(height_);
  for (uint32_t j = 0; j <= height_; ++j) rowCosines_[j] = std::cos(kPi * j / height_);
  for (uint32_t j = 0; j < height_; ++j) {
    const double texel = 2.0 * kPi / width_ * 2.0 * std::sin(kPi * (j + 0.5) / height_) * std::sin(kPi * 0.5 / height_);
    rowSolidAngle[j] = texel;
    texelSolidAngle_[j] = static_cast<float>(texel);
  }
  std::vector<double> weights(size_t(width_) * height_);
  double total = 0;
  for (size_t t = 0; t < weights.size(); ++t) {
    weights[t] = luminance(&image.pixels[4 * t]) * rowSolidAngle[t / width_];
    total += weights[t];
  }
  if (total == 0.0)
    for (size_t t = 0; t < weights.size(); ++t) weights[t] = rowSolidAngle[t / width_];

  std::vector<double> rowWeights(height_, 0.0);
  columnCdf_.reserve(size_t(width_ + 1) * height_);
  for (uint32_t j = 0; j < height_; ++j) {
    const double* row = &weights[size_t(j) * width_];
    for (uint32_t i = 0; i < width_; ++i) rowWeights[j] += row[i];
    appendCdf(row, width_, columnCdf_);
  }
  rowCdf_.reserve(height_ + 1);
  appendCdf(rowWeights.data(), height_, rowCdf_);
}

EnvironmentSample EnvironmentSampler::sample(const Vec2f& u) const {
  const CdfPick row = pickCell(rowCdf_.data(), height_, u.y());
  const CdfPick column = pickCell(&columnCdf_[size_t(row.cell) * (width_ + 1)], width_, u.x());
  // Uniform in cos θ between the row's edges: uniform in solid angle.
  const double cosTheta = rowCosines_[row.cell] + row.offset * (rowCosines_[row.cell + 1] - rowCosines_[row.cell]);
  const float v = static_cast<float>(std::acos(std::clamp(cosTheta, -1.0, 1.0)) / kPi);
  const Vec3f direction = directionFromLatLong((float(column.cell) + column.offset) / float(width_), v);
  // Read back through pdf() so a direction that rounds onto a neighbouring
  // texel carries that texel's density, as MIS will see it.
  return {direction, pdf(direction)};
}

float EnvironmentSampler::pdf(const Vec3f& direction) const {
  const Vec2i texel = latLongTexel(direction, width_, height_);
  const size_t row = size_t(texel.y()), column = size_t(texel.x());
  const float* columns = &columnCdf_[row * (width_ + 1)];
  const float probability = (rowCdf_[row + 1] - rowCdf_[row]) * (columns[column + 1] - columns[column]);
  return probability / texelSolidAngle_[row];
}

}  // namespace sdg
