// Importance sampling of lat-long domes: the density integrates to 1, the
// samples follow it texel by texel, one bright texel is sampled with no
// variance, the uniform and black maps give the uniform sphere, and the
// lat-long convention is render/latlong.h's.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "behavior/rng.h"
#include "render/latlong.h"
#include "render/pathtrace/environment_sampler.h"

using namespace sdg;

namespace {

constexpr double kPi = 3.14159265358979323846;

ImageRgbaF image(uint32_t width, uint32_t height, const std::function<float(uint32_t, uint32_t)>& grey) {
  ImageRgbaF result{width, height, std::vector<float>(size_t(width) * height * 4, 1.0f)};
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x)
      for (int c = 0; c < 3; ++c) result.pixels[4 * (size_t(y) * width + x) + size_t(c)] = grey(x, y);
  return result;
}

// A map with structure: a gradient, a dark band, a bright spot, colour.
ImageRgbaF testMap() {
  ImageRgbaF map = image(32, 16, [](uint32_t x, uint32_t y) {
    if (y == 5) return 0.0f;
    return 0.1f + 0.05f * float(x) + (x == 20 && y == 3 ? 40.0f : 0.0f);
  });
  map.pixels[4 * (10 * 32 + 7)] = 25.0f;  // a red texel
  return map;
}

// The solid angle of a texel of row y (exact: 2 pi / w (cos θtop - cos θbottom)).
double texelSolidAngle(uint32_t y, uint32_t width, uint32_t height) {
  return 2.0 * kPi / width * (std::cos(kPi * y / height) - std::cos(kPi * (y + 1) / height));
}

double luminance(const ImageRgbaF& map, size_t texel) {
  const float* p = &map.pixels[4 * texel];
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

// Points spread evenly over the sphere (a Fibonacci lattice).
std::vector<Vec3f> fibonacciSphere(int count) {
  std::vector<Vec3f> points;
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / count, r = std::sqrt(1.0 - z * z), phi = golden * i;
    points.emplace_back(float(r * std::cos(phi)), float(z), float(r * std::sin(phi)));
  }
  return points;
}

Vec2f uniform2(Rng& rng) { return Vec2f(float(rng.uniform01()), float(rng.uniform01())); }

}  // namespace

TEST_CASE("environment sampler: the pdf integrates to 1 over the sphere", "[pathtrace][environment]") {
  const EnvironmentSampler sampler(testMap());
  const std::vector<Vec3f> points = fibonacciSphere(400000);
  double sum = 0;
  for (const Vec3f& d : points) sum += sampler.pdf(d);
  CHECK(sum * 4.0 * kPi / double(points.size()) == Approx(1.0).epsilon(0.005));
}

TEST_CASE("environment sampler: texels are drawn in proportion to luminance times solid angle, uniformly inside",
          "[pathtrace][environment]") {
  const ImageRgbaF map = testMap();
  const EnvironmentSampler sampler(map);
  const uint32_t w = map.width, h = map.height;
  double total = 0;
  for (size_t t = 0; t < size_t(w) * h; ++t) total += luminance(map, t) * texelSolidAngle(uint32_t(t / w), w, h);

  // Buckets: each texel cut in 2 x 2 (halves of longitude and of cos θ,
  // equal solid angles), expecting a quarter of the texel's share.
  constexpr int kSamples = 200000;
  std::vector<double> observed(size_t(w) * h * 4, 0.0);
  Rng rng(1, 1);
  for (int n = 0; n < kSamples; ++n) {
    const EnvironmentSample s = sampler.sample(uniform2(rng));
    REQUIRE(s.pdf > 0.0f);
    CHECK(s.direction.norm() == Approx(1.0f).epsilon(1e-5));
    const Vec2i texel = latLongTexel(s.direction, w, h);
    const double u = latLongFromDirection(s.direction).x() * w - texel.x();
    const double top = std::cos(kPi * texel.y() / h), bottom = std::cos(kPi * (texel.y() + 1) / h);
    const int halfU = u >= 0.5 ? 1 : 0, halfCos = s.direction.y() < 0.5 * (top + bottom) ? 1 : 0;
    observed[4 * (size_t(texel.y()) * w + size_t(texel.x())) + size_t(2 * halfCos + halfU)] += 1.0;
  }
  double chi2 = 0;
  int buckets = 0;
  for (size_t t = 0; t < size_t(w) * h; ++t) {
    const double expected = kSamples * luminance(map, t) * texelSolidAngle(uint32_t(t / w), w, h) / total / 4.0;
    for (int q = 0; q < 4; ++q) {
      if (expected == 0.0) {
        CHECK(observed[4 * t + size_t(q)] == 0.0);  // the black row is never drawn
        continue;
      }
      chi2 += (observed[4 * t + size_t(q)] - expected) * (observed[4 * t + size_t(q)] - expected) / expected;
      ++buckets;
    }
  }
  const double dof = buckets - 1;
  INFO("chi2 " << chi2 << " over " << dof << " degrees of freedom");
  CHECK(chi2 < dof + 5.0 * std::sqrt(2.0 * dof));
}

TEST_CASE("environment sampler: a sample's pdf is pdf() of its direction", "[pathtrace][environment]") {
  const EnvironmentSampler sampler(testMap());
  Rng rng(2, 2);
  for (int n = 0; n < 10000; ++n) {
    const EnvironmentSample s = sampler.sample(uniform2(rng));
    CHECK(s.pdf == sampler.pdf(s.direction));
  }
  for (const Vec2f& u : {Vec2f(0, 0), Vec2f(0.99999994f, 0.99999994f), Vec2f(0, 0.99999994f)}) {
    const EnvironmentSample s = sampler.sample(u);
    CHECK((s.direction.allFinite() && std::isfinite(s.pdf) && s.pdf > 0.0f));
    CHECK(s.pdf == sampler.pdf(s.direction));
  }
}

TEST_CASE("environment sampler: one bright texel is sampled alone, with a zero-variance estimate",
          "[pathtrace][environment]") {
  constexpr uint32_t kX = 40, kY = 10;
  constexpr float kRadiance = 5000.0f;
  const ImageRgbaF map = image(64, 32, [](uint32_t x, uint32_t y) { return x == kX && y == kY ? kRadiance : 0.0f; });
  const EnvironmentSampler sampler(map);
  const double exact = kRadiance * texelSolidAngle(kY, 64, 32);
  Rng rng(3, 3);
  int inTexel = 0;
  double sum = 0, sumSquares = 0;
  constexpr int kSamples = 4096;
  for (int n = 0; n < kSamples; ++n) {
    const EnvironmentSample s = sampler.sample(uniform2(rng));
    const Vec2i texel = latLongTexel(s.direction, 64, 32);
    inTexel += texel == Vec2i(kX, kY);
    // The estimator of the dome's integral, L / pdf, reading L where the direction points.
    const double estimate = s.pdf > 0.0f ? map.pixels[4 * (size_t(texel.y()) * 64 + size_t(texel.x()))] / s.pdf : 0.0;
    sum += estimate, sumSquares += estimate * estimate;
  }
  const double mean = sum / kSamples, variance = sumSquares / kSamples - mean * mean;
  CHECK(inTexel >= kSamples - 2);  // a sample on the texel's very edge may round onto its neighbour
  CHECK(mean == Approx(exact).epsilon(1e-3));
  CHECK(std::sqrt(std::max(variance, 0.0)) / exact < 0.02);
}

TEST_CASE("environment sampler: uniform and black maps give the uniform sphere", "[pathtrace][environment]") {
  for (float value : {0.0f, 3.0f, -1.0f}) {
    const EnvironmentSampler sampler(image(16, 8, [value](uint32_t, uint32_t) { return value; }));
    for (const Vec3f& d : fibonacciSphere(1000)) CHECK(sampler.pdf(d) == Approx(1.0 / (4.0 * kPi)).epsilon(1e-5));
  }
  // Not-finite texels count as black.
  ImageRgbaF broken = image(16, 8, [](uint32_t, uint32_t) { return 1.0f; });
  broken.pixels[0] = std::numeric_limits<float>::infinity();
  broken.pixels[4 * 5 + 1] = std::numeric_limits<float>::quiet_NaN();
  const EnvironmentSampler sampler(broken);
  CHECK(sampler.pdf(directionFromLatLong(0.5f / 16.0f, 0.5f / 8.0f)) == 0.0f);
  CHECK(sampler.pdf(directionFromLatLong(5.5f / 16.0f, 0.5f / 8.0f)) == 0.0f);
  CHECK(sampler.pdf(directionFromLatLong(8.5f / 16.0f, 4.5f / 8.0f)) > 0.0f);
}

TEST_CASE("environment sampler: directions follow the lat-long convention", "[pathtrace][environment]") {
  // The centre of the image looks along +Z, a quarter in from the left
  // along +X, the top row up (+Y).
  auto brightAt = [](uint32_t bx, uint32_t by) {
    return EnvironmentSampler(image(64, 32, [=](uint32_t x, uint32_t y) { return x == bx && y == by ? 1.0f : 0.0f; }));
  };
  CHECK(brightAt(32, 16).sample(Vec2f(0.5f, 0.5f)).direction.z() > 0.99f);
  CHECK(brightAt(16, 16).sample(Vec2f(0.5f, 0.5f)).direction.x() > 0.99f);
  CHECK(brightAt(5, 0).sample(Vec2f(0.5f, 0.5f)).direction.y() > 0.99f);
  CHECK(brightAt(5, 31).sample(Vec2f(0.5f, 0.5f)).direction.y() < -0.99f);
}
