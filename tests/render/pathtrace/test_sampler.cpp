// The path tracer's per-pixel sample streams: Owen-scrambled Sobol pairs
// (Burley 2020). Deterministic, in [0, 1), stratified as a (0,2)-sequence,
// better than random on smooth integrands, and decorrelated across pixels,
// frames and slots.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <thread>
#include <vector>

#include "behavior/rng.h"
#include "render/pathtrace/sampler.h"

using namespace sdg;

namespace {

// The points of one slot (the `slot`-th draw) of samples [first, first + count).
std::vector<Vec2f> slotPoints(uint64_t frameSeed, uint32_t x, uint32_t y, int slot, uint32_t first, uint32_t count) {
  PixelSampler sampler(frameSeed, x, y);
  std::vector<Vec2f> points;
  for (uint32_t i = first; i < first + count; ++i) {
    sampler.startSample(i);
    for (int s = 0; s < slot; ++s) (s % 3 == 2) ? void(sampler.next1D()) : void(sampler.next2D());
    points.push_back(sampler.next2D());
  }
  return points;
}

// Every elementary interval of area 1/count (2^a by 2^b cells, a + b =
// log2(count)) holds exactly one point: the (0,m,2)-net property.
bool isZeroNet(const std::vector<Vec2f>& points) {
  int m = 0;
  while ((size_t{1} << m) < points.size()) ++m;
  for (int a = 0; a <= m; ++a) {
    const int columns = 1 << a, rows = 1 << (m - a);
    std::vector<int> counts(points.size(), 0);
    for (const Vec2f& p : points)
      ++counts[size_t(int(p.y() * float(rows)) * columns + int(p.x() * float(columns)))];
    for (int c : counts)
      if (c != 1) return false;
  }
  return true;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  double ma = 0, mb = 0;
  for (size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= double(a.size()), mb /= double(b.size());
  double sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

// A smooth integrand over the unit square and its exact integral.
double smooth(double x, double y) { return std::exp(x) * std::sin(3.0 * y + 0.5); }
const double kSmoothIntegral = (std::exp(1.0) - 1.0) * (std::cos(0.5) - std::cos(3.5)) / 3.0;

}  // namespace

TEST_CASE("sampler: unscrambled Sobol matches Joe-Kuo's first two dimensions", "[pathtrace][sampler]") {
  // In index order (Joe-Kuo list the points in Gray-code order: the same
  // points, blocks of 2^k permuted within themselves).
  const double dim0[] = {0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875};
  const double dim1[] = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
  for (uint32_t i = 0; i < 8; ++i) {
    CHECK(double(sobol(i, 0)) * 0x1p-32 == dim0[i]);
    CHECK(double(sobol(i, 1)) * 0x1p-32 == dim1[i]);
  }
}

TEST_CASE("sampler: values lie in the unit interval and streams depend only on seed, pixel, index and slot",
          "[pathtrace][sampler]") {
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x) {
      PixelSampler a(42, x, y), b(42, x, y);
      for (uint32_t i = 0; i < 64; ++i) {
        a.startSample(i);
        b.startSample(i);
        for (int slot = 0; slot < 8; ++slot) {
          const Vec2f p = a.next2D(), q = b.next2D();
          CHECK((p == q));
          CHECK((p.x() >= 0.0f && p.x() < 1.0f && p.y() >= 0.0f && p.y() < 1.0f));
          const float u = a.next1D();
          CHECK(u == b.next1D());
          CHECK((u >= 0.0f && u < 1.0f));
        }
      }
    }
  // Jumping straight to a sample gives what drawing every earlier one did.
  PixelSampler walked(7, 3, 9), jumped(7, 3, 9);
  for (uint32_t i = 0; i <= 100; ++i) {
    walked.startSample(i);
    walked.next2D();
  }
  walked.startSample(77);
  jumped.startSample(77);
  CHECK((walked.next2D() == jumped.next2D()));
  // Drawn on other threads, in another order: the same streams.
  std::vector<std::vector<Vec2f>> sequential, threaded(8);
  for (uint32_t pixel = 0; pixel < 8; ++pixel) sequential.push_back(slotPoints(3, pixel, 1, 2, 0, 32));
  {
    std::vector<std::jthread> workers;
    for (uint32_t pixel = 8; pixel-- > 0;)
      workers.emplace_back([&threaded, pixel] { threaded[pixel] = slotPoints(3, pixel, 1, 2, 0, 32); });
  }
  CHECK((threaded == sequential));
  // Another frame, another pixel: another stream.
  CHECK((slotPoints(1, 0, 0, 0, 0, 4) != slotPoints(2, 0, 0, 0, 0, 4)));
  CHECK((slotPoints(1, 0, 0, 0, 0, 4) != slotPoints(1, 1, 0, 0, 0, 4)));
  CHECK((slotPoints(1, 0, 0, 0, 0, 4) != slotPoints(1, 0, 1, 0, 0, 4)));
}

TEST_CASE("sampler: every slot's power-of-two blocks are (0,m,2)-nets after scrambling", "[pathtrace][sampler]") {
  for (uint32_t pixel = 0; pixel < 6; ++pixel)
    for (int slot = 0; slot < 6; ++slot) {
      INFO("pixel " << pixel << " slot " << slot);
      // 256 samples: every 1x256, 2x128, ..., 16x16, ..., 256x1 grid.
      CHECK(isZeroNet(slotPoints(5, pixel, 2 * pixel, slot, 0, 256)));
      // Progressive: the first 64 and the next block of 64 on their own.
      CHECK(isZeroNet(slotPoints(5, pixel, 2 * pixel, slot, 0, 64)));
      CHECK(isZeroNet(slotPoints(5, pixel, 2 * pixel, slot, 64, 64)));
    }
  // A 1D slot: 256 values, one in each 1/256 interval.
  PixelSampler sampler(5, 1, 1);
  std::vector<int> counts(256, 0);
  for (uint32_t i = 0; i < 256; ++i) {
    sampler.startSample(i);
    sampler.next2D();
    ++counts[size_t(sampler.next1D() * 256.0f)];
  }
  CHECK(std::count(counts.begin(), counts.end(), 1) == 256);
}

TEST_CASE("sampler: a smooth 2D integral converges much faster than with random points", "[pathtrace][sampler]") {
  constexpr uint32_t kSamples = 256;
  constexpr uint32_t kPixels = 64;
  Rng rng(11, 3);
  double sobolError = 0, randomError = 0;
  for (uint32_t pixel = 0; pixel < kPixels; ++pixel) {
    PixelSampler sampler(3, pixel, 5);
    double sobolSum = 0, randomSum = 0;
    for (uint32_t i = 0; i < kSamples; ++i) {
      sampler.startSample(i);
      const Vec2f p = sampler.next2D();
      sobolSum += smooth(p.x(), p.y());
      randomSum += smooth(rng.uniform01(), rng.uniform01());
    }
    sobolError += std::abs(sobolSum / kSamples - kSmoothIntegral);
    randomError += std::abs(randomSum / kSamples - kSmoothIntegral);
  }
  INFO("mean absolute error: scrambled Sobol " << sobolError / kPixels << ", random " << randomError / kPixels);
  CHECK(sobolError < randomError / 3.0);
}

TEST_CASE("sampler: pixels and slots are decorrelated", "[pathtrace][sampler]") {
  // Per-pixel estimates of the smooth integral: neighbours' errors are
  // independent (the scramble, not the net, decides them).
  constexpr uint32_t kSide = 48;
  std::vector<double> error(kSide * kSide);
  for (uint32_t y = 0; y < kSide; ++y)
    for (uint32_t x = 0; x < kSide; ++x) {
      double sum = 0;
      for (const Vec2f& p : slotPoints(9, x, y, 0, 0, 16)) sum += smooth(p.x(), p.y());
      error[y * kSide + x] = sum / 16 - kSmoothIntegral;
    }
  std::vector<double> left, right, up, down;
  for (uint32_t y = 0; y + 1 < kSide; ++y)
    for (uint32_t x = 0; x + 1 < kSide; ++x) {
      left.push_back(error[y * kSide + x]), right.push_back(error[y * kSide + x + 1]);
      up.push_back(error[y * kSide + x]), down.push_back(error[(y + 1) * kSide + x]);
    }
  CHECK(std::abs(correlation(left, right)) < 0.1);
  CHECK(std::abs(correlation(up, down)) < 0.1);

  // Slots of one pixel: the first coordinates of slot 0 and slot 1 over 256
  // samples are independent (mean r^2 near 1/256, as for random pairs), not
  // the same net twice.
  double meanSquaredR = 0;
  constexpr int kPixels = 64;
  for (uint32_t pixel = 0; pixel < kPixels; ++pixel) {
    PixelSampler sampler(9, pixel, 0);
    std::vector<double> first, second;
    for (uint32_t i = 0; i < 256; ++i) {
      sampler.startSample(i);
      first.push_back(sampler.next2D().x());
      second.push_back(sampler.next2D().x());
    }
    const double r = correlation(first, second);
    meanSquaredR += r * r / kPixels;
  }
  CHECK(meanSquaredR < 3.0 / 256.0);
}

TEST_CASE("sampler: the streams' numbers are pinned (the GPU tracer's GLSL port draws the same)",
          "[pathtrace][sampler]") {
  // An FNV-1a hash of the bits of mixed 1D and 2D draws, 60 slots a sample
  // (beyond the sampler's cached slots), jumps in the sample index, three
  // frame seeds. A change here changes every path-traced frame and must be
  // made in gpu/shaders/pt_common.glsl too.
  uint64_t hash = 0xcbf29ce484222325ull;
  auto add = [&hash](float v) {
    uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int k = 0; k < 4; ++k) hash = (hash ^ ((bits >> (8 * k)) & 0xffu)) * 0x100000001b3ull;
  };
  for (uint64_t seed : {uint64_t{0}, uint64_t{10}, uint64_t{0xfedcba9876543210ull}})
    for (uint32_t y = 0; y < 5; ++y)
      for (uint32_t x = 0; x < 5; ++x) {
        PixelSampler sampler(seed, x * 37, y * 101);
        for (uint32_t i = 0; i < 70; ++i) {
          sampler.startSample(i * (i % 7 == 6 ? 977u : 1u));
          for (int slot = 0; slot < 60; ++slot) {
            if (slot % 3 == 1) {
              add(sampler.next1D());
            } else {
              const Vec2f p = sampler.next2D();
              add(p.x());
              add(p.y());
            }
          }
        }
      }
  CHECK(hash == 0x635d65b5de8d53e7ull);
}
