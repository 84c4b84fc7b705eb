// Pre-filtering of lat-long domes for image-based lighting: irradiance
// against analytic values, the specular chain's levels, the split-sum table
// against a brute-force integral, determinism across thread counts.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "render/raster/environment_map.h"
#include "render/latlong.h"

using namespace sdg;

namespace {

constexpr double kPi = 3.14159265358979323846;

ImageRgbaF filled(uint32_t width, uint32_t height, const Vec3f& radiance) {
  ImageRgbaF map{width, height, {}};
  for (size_t i = 0; i < size_t(width) * height; ++i)
    map.pixels.insert(map.pixels.end(), {radiance.x(), radiance.y(), radiance.z(), 1.0f});
  return map;
}

void setTexel(ImageRgbaF& map, uint32_t x, uint32_t y, const Vec3f& radiance) {
  float* p = map.pixels.data() + 4 * (size_t(y) * map.width + x);
  p[0] = radiance.x(), p[1] = radiance.y(), p[2] = radiance.z();
}

// A fixed pattern with detail at every scale: a hash of the texel.
ImageRgbaF noisy(uint32_t width, uint32_t height) {
  ImageRgbaF map = filled(width, height, Vec3f::Zero());
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      uint32_t h = (x * 73856093u) ^ (y * 19349663u);
      h = (h ^ (h >> 13)) * 0x5bd1e995u;
      const float a = float(h % 1000) / 100.0f, b = float((h >> 10) % 1000) / 100.0f;
      setTexel(map, x, y, Vec3f(a, b, 0.5f * (a + b)));
    }
  return map;
}

Vec3f texelDirection(uint32_t width, uint32_t height, uint32_t x, uint32_t y) {
  return directionFromLatLong((float(x) + 0.5f) / float(width), (float(y) + 0.5f) / float(height));
}

// The integral of radiance over the sphere, per channel.
Vec3d integral(const ImageRgbaF& map) {
  Vec3d sum = Vec3d::Zero();
  for (uint32_t y = 0; y < map.height; ++y)
    for (uint32_t x = 0; x < map.width; ++x) {
      const float* p = map.pixels.data() + 4 * (size_t(y) * map.width + x);
      sum += Vec3d(p[0], p[1], p[2]) * latLongTexelSolidAngle(int(map.width), int(map.height), int(y));
    }
  return sum;
}

Vec3d integral(const LatLong& image) {
  Vec3d sum = Vec3d::Zero();
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float* p = image.rgb.data() + 3 * (size_t(y) * size_t(image.width) + size_t(x));
      sum += Vec3d(p[0], p[1], p[2]) * latLongTexelSolidAngle(image.width, image.height, y);
    }
  return sum;
}

Vec3f texel(const LatLong& image, int x, int y) {
  return Eigen::Map<const Vec3f>(image.rgb.data() + 3 * (size_t(y) * size_t(image.width) + size_t(x)));
}

// `dir` turned by `degrees` towards some direction perpendicular to it.
Vec3f turned(const Vec3f& dir, float degrees) {
  const Vec3f axis = dir.cross(std::abs(dir.y()) < 0.9f ? Vec3f::UnitY() : Vec3f::UnitX()).normalized();
  return Eigen::AngleAxisf(degrees * kLatLongPi / 180.0f, axis) * dir;
}

// The specular BRDF of shaders.h's brdf() without F0, integrated over the
// hemisphere on a fine grid: (the part multiplying F0, the part added).
Eigen::Vector2d bruteForceSplitSum(double nv, double roughness) {
  const double alpha = std::max(roughness * roughness, 1e-3), a2 = alpha * alpha, k = alpha / 2.0;
  const Vec3d v(std::sqrt(1.0 - nv * nv), 0.0, nv);
  const int steps = 2048;
  const double dTheta = kPi / 2.0 / steps, dPhi = 2.0 * kPi / (2 * steps);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (int i = 0; i < steps; ++i) {
    const double theta = (i + 0.5) * dTheta;
    for (int j = 0; j < 2 * steps; ++j) {
      const double phi = (j + 0.5) * dPhi;
      const Vec3d l(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      const Vec3d h = (l + v).normalized();
      const double nl = l.z(), nh = h.z(), vh = v.dot(h);
      const double denominator = nh * nh * (a2 - 1.0) + 1.0;
      const double d = a2 / (kPi * denominator * denominator);
      const double g = (nl / (nl * (1.0 - k) + k)) * (nv / (nv * (1.0 - k) + k));
      const double fresnel = std::pow(1.0 - vh, 5.0);
      const double f = d * g / (4.0 * nl * nv) * nl * std::sin(theta) * dTheta * dPhi;
      sum += Eigen::Vector2d((1.0 - fresnel) * f, fresnel * f);
    }
  }
  return sum;
}

Eigen::Vector2f lutAt(const SplitSumLut& lut, int i, int j) {
  const size_t k = 2 * (size_t(j) * size_t(lut.size) + size_t(i));
  return {lut.scaleBias[k], lut.scaleBias[k + 1]};
}

}  // namespace

TEST_CASE("environment: texel solid angles cover the sphere, bilinear reads wrap in u, clamp in v", "[render][environment]") {
  double total = 0;
  for (int y = 0; y < 1000; ++y) total += 2000 * latLongTexelSolidAngle(2000, 1000, y);
  CHECK(total == Approx(4.0 * kPi).epsilon(1e-12));
  // A texel at the pole keeps its precision (the difference of two cosines
  // near 1 would lose it): (2 pi / w) (1 - cos(pi / h)).
  CHECK(latLongTexelSolidAngle(4096, 2048, 0) == Approx(2.0 * kPi / 4096 * 2.0 * std::pow(std::sin(kPi / 4096), 2)).epsilon(1e-12));

  // Clamped in v: above the top row's centres it reads the top row alone.
  LatLong image{4, 2, std::vector<float>(4 * 2 * 3, 0.0f)};
  image.rgb[0] = 1.0f;          // the first column of the top row
  image.rgb[3 * 3 + 1] = 1.0f;  // the last one
  for (size_t i = 4 * 3; i < image.rgb.size(); ++i) image.rgb[i] = 7.0f;  // the bottom row
  const Vec3f seam = sampleBilinear(image, directionFromLatLong(0.0f, 0.1f));
  CHECK(seam.isApprox(Vec3f(0.5f, 0.5f, 0.0f)));
  CHECK(sampleBilinear(image, directionFromLatLong(0.125f, 0.1f)).isApprox(Vec3f(1.0f, 0.0f, 0.0f)));
  CHECK(sampleBilinear(image, -Vec3f::UnitY()).isApprox(Vec3f::Constant(7.0f)));
}

TEST_CASE("environment: a constant dome gives its radiance everywhere", "[render][environment]") {
  const Vec3f radiance(2.0f, 0.5f, 1.0f);
  const PrefilteredEnvironment env = prefilterEnvironment(filled(1024, 512, radiance));
  REQUIRE((env.irradiance.width == 64 && env.irradiance.height == 32));
  REQUIRE(env.specular.size() == 6);
  for (int y = 0; y < env.irradiance.height; ++y)
    for (int x = 0; x < env.irradiance.width; ++x)
      for (int c = 0; c < 3; ++c) CHECK(texel(env.irradiance, x, y)[c] == Approx(radiance[c]).epsilon(0.005));
  int width = 512, height = 256;
  for (const LatLong& level : env.specular) {
    CHECK((level.width == width && level.height == height));
    for (int y = 0; y < level.height; ++y)
      for (int x = 0; x < level.width; ++x)
        for (int c = 0; c < 3; ++c) CHECK(texel(level, x, y)[c] == Approx(radiance[c]).epsilon(0.005));
    width /= 2, height /= 2;
  }
}

TEST_CASE("environment: one bright texel lights the normals facing it by L * solid angle * cos", "[render][environment]") {
  constexpr uint32_t kWidth = 1024, kHeight = 512;
  const float radiance = 1000.0f;
  // Rows near the equator and at 60 degrees of latitude, at columns that fall
  // between the irradiance map's texels.
  for (const auto& [x, y] : {std::pair<uint32_t, uint32_t>{301, 255}, {700, 85}}) {
    CAPTURE(x, y);
    ImageRgbaF map = filled(kWidth, kHeight, Vec3f::Zero());
    setTexel(map, x, y, Vec3f::Constant(radiance));
    const PrefilteredEnvironment env = prefilterEnvironment(map);
    const Vec3f dir = texelDirection(kWidth, kHeight, x, y);
    const double expected = radiance * latLongTexelSolidAngle(int(kWidth), int(kHeight), int(y));
    const Vec3f facing = sampleBilinear(env.irradiance, dir) * float(kPi);
    CHECK(facing.x() == Approx(expected).epsilon(0.01));
    CHECK(sampleBilinear(env.irradiance, turned(dir, 60.0f)).x() * kPi == Approx(0.5 * expected).epsilon(0.02));
    CHECK(sampleBilinear(env.irradiance, -dir).x() == 0.0f);
    // The peak is at that normal: every texel of the map is dimmer.
    for (int j = 0; j < env.irradiance.height; ++j)
      for (int i = 0; i < env.irradiance.width; ++i) CHECK(texel(env.irradiance, i, j).x() * kPi <= expected * 1.0001);
  }
}

TEST_CASE("environment: sky over ground", "[render][environment]") {
  const Vec3f sky(4.0f, 4.0f, 5.0f), ground(0.5f, 0.4f, 0.3f);
  ImageRgbaF map = filled(512, 256, ground);
  for (uint32_t y = 0; y < 128; ++y)
    for (uint32_t x = 0; x < 512; ++x) setTexel(map, x, y, sky);
  const PrefilteredEnvironment env = prefilterEnvironment(map);
  const Vec3f up = sampleBilinear(env.irradiance, Vec3f::UnitY());
  const Vec3f down = sampleBilinear(env.irradiance, -Vec3f::UnitY());
  const Vec3f horizontal = sampleBilinear(env.irradiance, Vec3f(0.6f, 0.0f, 0.8f));
  for (int c = 0; c < 3; ++c) {
    CHECK(up[c] == Approx(sky[c]).epsilon(0.01));
    CHECK(down[c] == Approx(ground[c]).epsilon(0.01));
    CHECK(horizontal[c] == Approx(0.5f * (sky[c] + ground[c])).epsilon(0.01));
  }
}

TEST_CASE("environment: specular level 0 is the dome downsampled by solid angle", "[render][environment]") {
  // 1024 x 512 -> 512 x 256: each texel averages 2 x 2, the two rows
  // weighted by their solid angles.
  const ImageRgbaF map = noisy(1024, 512);
  const LatLong level0 = prefilterEnvironment(map).specular[0];
  REQUIRE((level0.width == 512 && level0.height == 256));
  for (int y = 0; y < 256; y += 17)
    for (int x = 0; x < 512; x += 13) {
      Vec3d sum = Vec3d::Zero();
      double weights = 0;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const double w = latLongTexelSolidAngle(1024, 512, 2 * y + dy);
          const float* p = map.pixels.data() + 4 * (size_t(2 * y + dy) * 1024 + size_t(2 * x + dx));
          sum += w * Vec3d(p[0], p[1], p[2]);
          weights += w;
        }
      for (int c = 0; c < 3; ++c) CHECK(texel(level0, x, y)[c] == Approx(sum[c] / weights).epsilon(1e-5));
    }
}

TEST_CASE("environment: downsampling keeps the integral over the sphere", "[render][environment]") {
  // An even ratio and an uneven one (1000 -> 512).
  for (const auto& [width, height] : {std::pair<uint32_t, uint32_t>{2048, 1024}, {1000, 500}}) {
    CAPTURE(width, height);
    const ImageRgbaF map = noisy(width, height);
    const Vec3d before = integral(map), after = integral(prefilterEnvironment(map).specular[0]);
    for (int c = 0; c < 3; ++c) CHECK(after[c] == Approx(before[c]).epsilon(0.001));
  }
}

TEST_CASE("environment: the roughest level spreads one texel over a wide lobe, keeping its energy", "[render][environment]") {
  ImageRgbaF map = filled(512, 256, Vec3f::Zero());
  setTexel(map, 200, 100, Vec3f::Constant(1000.0f));
  const PrefilteredEnvironment env = prefilterEnvironment(map);
  const LatLong& roughest = env.specular.back();
  CHECK(integral(roughest).x() == Approx(integral(map).x()).epsilon(0.03));
  // For roughness 1 (alpha = 1), GGX spreads L uniformly over the sphere,
  // so with the N.L weight the level is the clamped cosine lobe: exactly the
  // irradiance map. Filtered importance sampling blurs it a little, and must
  // show no ghosts of single samples.
  float peak = 0, error = 0;
  for (int y = 0; y < roughest.height; ++y)
    for (int x = 0; x < roughest.width; ++x) {
      const float lobe = sampleBilinear(env.irradiance, texelDirection(uint32_t(roughest.width), uint32_t(roughest.height),
                                                                        uint32_t(x), uint32_t(y))).x();
      peak = std::max(peak, lobe);
      error = std::max(error, std::abs(texel(roughest, x, y).x() - lobe));
    }
  CHECK(error < 0.12f * peak);
}

TEST_CASE("environment: the split-sum table", "[render][environment]") {
  const SplitSumLut lut = integrateSplitSumLut(32);
  REQUIRE(lut.scaleBias.size() == 32 * 32 * 2);
  // A mirror seen head-on reflects everything, all of it through F0.
  const Eigen::Vector2f mirror = lutAt(lut, 31, 0);
  CHECK(mirror.sum() == Approx(1.0f).epsilon(0.01));
  CHECK(mirror.y() < 0.001f);
  // Roughness about 0 is a mirror: all of it at the Fresnel of N.V, but
  // for Smith-Schlick's G1(N.V)^2 (alpha clamped to 1e-3).
  for (int i = 0; i < 32; ++i) {
    CAPTURE(i);
    const double nv = (i + 0.5) / 32.0, k = 0.5e-3, g1 = nv / (nv * (1.0 - k) + k), fresnel = std::pow(1.0 - nv, 5.0);
    CHECK(lutAt(lut, i, 0).x() == Approx(g1 * g1 * (1.0 - fresnel)).margin(0.005));
    CHECK(lutAt(lut, i, 0).y() == Approx(g1 * g1 * fresnel).margin(0.005));
  }
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) {
      CAPTURE(i, j);
      const Eigen::Vector2f v = lutAt(lut, i, j);
      CHECK((v.x() >= 0.0f && v.y() >= 0.0f));
      CHECK(v.sum() <= 1.0f + 1e-4f);
      // Away from grazing views (where Schlick's G is not monotone): the
      // Fresnel part falls as the view turns towards the normal; rougher
      // surfaces reflect less (more is shadowed and masked); the part
      // through F0 grows towards the normal unless the surface is rough.
      if (i >= 2) CHECK(v.y() <= lutAt(lut, i - 1, j).y() + 1e-4f);
      if (i >= 6 && j > 0) CHECK(v.sum() <= lutAt(lut, i, j - 1).sum() + 1e-4f);
      if (i >= 6 && j < 16) CHECK(v.x() >= lutAt(lut, i - 1, j).x() - 1e-4f);
    }
  for (const auto& [i, j] : {std::pair<int, int>{16, 16}, {8, 24}, {28, 10}}) {
    CAPTURE(i, j);
    const Eigen::Vector2d expected = bruteForceSplitSum((i + 0.5) / 32.0, (j + 0.5) / 32.0);
    CHECK(lutAt(lut, i, j).x() == Approx(expected.x()).epsilon(0.01));
    CHECK(lutAt(lut, i, j).y() == Approx(expected.y()).epsilon(0.01));
  }
}

TEST_CASE("environment: the result does not depend on the thread count", "[render][environment]") {
  const ImageRgbaF map = noisy(1000, 500);
  EnvironmentSettings one, three;
  one.threads = 1;
  three.threads = 3;
  const PrefilteredEnvironment a = prefilterEnvironment(map, one), b = prefilterEnvironment(map, three);
  CHECK(a.irradiance.rgb == b.irradiance.rgb);
  REQUIRE(a.specular.size() == b.specular.size());
  for (size_t k = 0; k < a.specular.size(); ++k) CHECK(a.specular[k].rgb == b.specular[k].rgb);
}

TEST_CASE("environment: bench, a 4096 x 2048 dome", "[.bench]") {
  const ImageRgbaF map = noisy(4096, 2048);
  for (int threads : {1, 2}) {
    EnvironmentSettings settings;
    settings.threads = threads;
    double best = 1e9;
    for (int run = 0; run < 5; ++run) {
      const auto start = std::chrono::steady_clock::now();
      const PrefilteredEnvironment env = prefilterEnvironment(map, settings);
      best = std::min(best, std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::printf("prefilterEnvironment 4096 x 2048, %d thread(s): %.1f ms (best of 5)\n", threads, best);
  }
  const auto start = std::chrono::steady_clock::now();
  const SplitSumLut lut = integrateSplitSumLut(32);
  std::printf("integrateSplitSumLut(32): %.1f ms\n",
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
}
