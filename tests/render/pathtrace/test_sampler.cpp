// The path tracer's sample streams: Owen-scrambled Sobol pairs (Burley
// 2020) in the Z-sampler's order (Ahmed and Wonka 2020). Deterministic, in
// [0, 1), stratified as a (0,2)-sequence per pixel and over every aligned
// block of pixels, better than random on smooth integrands, and
// decorrelated across tiles, frames and slots.
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

// The points of one slot (the `slot`-th draw) of samples [first, first + count)
// of pixel (x, y) in a frame of `spp` samples per pixel.
std::vector<Vec2f> slotPoints(uint64_t frameSeed, uint32_t spp, uint32_t x, uint32_t y, int slot, uint32_t first,
                              uint32_t count) {
  SamplerTile tile(frameSeed, spp, x, y);
  PixelSampler sampler(tile, x, y);
  std::vector<Vec2f> points;
  for (uint32_t i = first; i < first + count; ++i) {
    sampler.startSample(i);
    for (int s = 0; s < slot; ++s) (s % 3 == 2) ? void(sampler.next1D()) : void(sampler.next2D());
    points.push_back(sampler.next2D());
  }
  return points;
}

// One slot's points of every sample of the side x side pixels from (x0, y0).
std::vector<Vec2f> blockPoints(uint64_t frameSeed, uint32_t spp, uint32_t x0, uint32_t y0, uint32_t side, int slot) {
  std::vector<Vec2f> points;
  for (uint32_t y = y0; y < y0 + side; ++y)
    for (uint32_t x = x0; x < x0 + side; ++x) {
      const std::vector<Vec2f> pixel = slotPoints(frameSeed, spp, x, y, slot, 0, spp);
      points.insert(points.end(), pixel.begin(), pixel.end());
    }
  return points;
}

// The most points in one elementary interval of area 2^-m (2^a by 2^b
// cells, a + b = m). 1 for 2^m points: the (0,m,2)-net property.
int mostInAnInterval(const std::vector<Vec2f>& points, int m) {
  int most = 0;
  for (int a = 0; a <= m; ++a) {
    const int columns = 1 << a, rows = 1 << (m - a);
    std::vector<int> counts(size_t(1) << m, 0);
    for (const Vec2f& p : points)
      most = std::max(most, ++counts[size_t(int(p.y() * float(rows)) * columns + int(p.x() * float(columns)))]);
  }
  return most;
}
bool isZeroNet(const std::vector<Vec2f>& points) {
  int m = 0;
  while ((size_t{1} << m) < points.size()) ++m;
  return (size_t{1} << m) == points.size() && mostInAnInterval(points, m) == 1;
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

// Each pixel's error on the smooth integral (slot 0, `spp` samples) over a
// width x height image from (0, 0).
std::vector<double> pixelErrors(uint64_t frameSeed, uint32_t spp, uint32_t width, uint32_t height) {
  std::vector<double> error;
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      double sum = 0;
      for (const Vec2f& p : slotPoints(frameSeed, spp, x, y, 0, 0, spp)) sum += smooth(p.x(), p.y());
      error.push_back(sum / spp - kSmoothIntegral);
    }
  return error;
}

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

TEST_CASE("sampler: the Z-order fits a tile's pixels and samples in 32-bit indices for any sample count",
          "[pathtrace][sampler]") {
  struct Case {
    uint32_t spp, sampleBits, tileBits;
  };
  for (const Case& c : {Case{1, 0, 6}, Case{2, 1, 6}, Case{3, 2, 6}, Case{4, 2, 6}, Case{5, 3, 6}, Case{1024, 10, 6},
                        Case{1u << 20, 20, 6}, Case{(1u << 20) + 1, 21, 5}, Case{1u << 24, 24, 4},
                        Case{1u << 31, 31, 0}, Case{0xffffffffu, 32, 0}}) {
    INFO("samples " << c.spp);
    const SampleLayout layout(c.spp);
    CHECK(layout.sampleBits == c.sampleBits);
    CHECK(layout.tileBits == c.tileBits);
    CHECK(layout.sampleBits + 2 * layout.tileBits <= 32);
    // The tile's last pixel's last sample is the largest index; the tile's
    // pixels' ranges do not overlap, and another tile's pixel starts over.
    const uint32_t last = (1u << layout.tileBits) - 1;
    CHECK(uint64_t(layout.indexBase(last, last)) + (c.spp - 1) < (uint64_t{1} << 32));
    if (layout.tileBits > 0) {
      CHECK(layout.indexBase(1, 0) == uint32_t(uint64_t{1} << layout.sampleBits));
      CHECK(layout.indexBase(0, 1) == uint32_t(uint64_t{2} << layout.sampleBits));
    }
    CHECK(layout.indexBase(last + 1, last + 1) == 0);
  }
  // Tiles: 64 x 64 pixels, 8 x 8 at 2^25 samples (the CPU tracer's 16 x 16 tiles then span four).
  CHECK(SamplerTile(1, 64, 70, 10).holds(127, 63));
  CHECK_FALSE(SamplerTile(1, 64, 70, 10).holds(128, 10));
  CHECK_FALSE(SamplerTile(1, 64, 70, 10).holds(63, 10));
  CHECK(SamplerTile(1, 1u << 25, 13, 5).holds(8, 7));
  CHECK_FALSE(SamplerTile(1, 1u << 25, 13, 5).holds(16, 5));
  // Morton order: each aligned 2^k x 2^k block of pixels is one aligned block of 4^k codes.
  const SampleLayout layout(1);
  std::vector<uint32_t> codes;
  for (uint32_t y = 8; y < 16; ++y)
    for (uint32_t x = 24; x < 32; ++x) codes.push_back(layout.indexBase(x, y));
  std::sort(codes.begin(), codes.end());
  CHECK(codes.front() % 64 == 0);
  CHECK(codes.back() == codes.front() + 63);
  CHECK(std::adjacent_find(codes.begin(), codes.end()) == codes.end());
}

TEST_CASE("sampler: values lie in the unit interval and streams depend only on seed, samples, pixel, index and slot",
          "[pathtrace][sampler]") {
  for (uint32_t y = 0; y < 4; ++y)
    for (uint32_t x = 0; x < 4; ++x) {
      SamplerTile tileA(42, 64, x, y), tileB(42, 64, x, y);
      PixelSampler a(tileA, x, y), b(tileB, x, y);
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
  SamplerTile tile(7, 128, 3, 9);
  PixelSampler walked(tile, 3, 9), jumped(tile, 3, 9);
  for (uint32_t i = 0; i <= 100; ++i) {
    walked.startSample(i);
    walked.next2D();
  }
  walked.startSample(77);
  jumped.startSample(77);
  CHECK((walked.next2D() == jumped.next2D()));
  // Pixels sharing one tile's keys, drawn interleaved, 60 slots deep (past
  // the cached keys): what each draws alone.
  SamplerTile shared(7, 4, 5, 6);
  PixelSampler first(shared, 5, 6), second(shared, 6, 6);
  std::vector<float> together[2];
  for (uint32_t i = 0; i < 4; ++i) {
    first.startSample(i);
    second.startSample(i);
    for (int slot = 0; slot < 60; ++slot) {
      together[0].push_back(first.next1D());
      if (slot % 2) together[1].push_back(second.next1D());
      else together[1].push_back(second.next2D().y());
    }
  }
  for (uint32_t pixel = 0; pixel < 2; ++pixel) {
    SamplerTile own(7, 4, 5 + pixel, 6);
    PixelSampler alone(own, 5 + pixel, 6);
    std::vector<float> drawn;
    for (uint32_t i = 0; i < 4; ++i) {
      alone.startSample(i);
      for (int slot = 0; slot < 60; ++slot)
        drawn.push_back(pixel == 0 || slot % 2 ? alone.next1D() : alone.next2D().y());
    }
    CHECK((drawn == together[pixel]));
  }
  // Drawn on other threads, in another order: the same streams.
  std::vector<std::vector<Vec2f>> sequential, threaded(8);
  for (uint32_t pixel = 0; pixel < 8; ++pixel) sequential.push_back(slotPoints(3, 32, pixel, 1, 2, 0, 32));
  {
    std::vector<std::jthread> workers;
    for (uint32_t pixel = 8; pixel-- > 0;)
      workers.emplace_back([&threaded, pixel] { threaded[pixel] = slotPoints(3, 32, pixel, 1, 2, 0, 32); });
  }
  CHECK((threaded == sequential));
  // Another frame, pixel or sample count: another stream.
  CHECK((slotPoints(1, 4, 0, 0, 0, 0, 4) != slotPoints(2, 4, 0, 0, 0, 0, 4)));
  CHECK((slotPoints(1, 4, 0, 0, 0, 0, 4) != slotPoints(1, 4, 1, 0, 0, 0, 4)));
  CHECK((slotPoints(1, 4, 0, 0, 0, 0, 4) != slotPoints(1, 4, 0, 1, 0, 0, 4)));
  CHECK((slotPoints(1, 4, 1, 0, 0, 0, 4) != slotPoints(1, 8, 1, 0, 0, 0, 4)));
}

TEST_CASE("sampler: each pixel's power-of-two blocks of samples are (0,m,2)-nets", "[pathtrace][sampler]") {
  for (uint32_t pixel = 0; pixel < 6; ++pixel)
    for (int slot = 0; slot < 6; ++slot) {
      INFO("pixel " << pixel << " slot " << slot);
      // 256 samples: every 1x256, 2x128, ..., 16x16, ..., 256x1 grid.
      CHECK(isZeroNet(slotPoints(5, 256, 7 * pixel, 2 * pixel, slot, 0, 256)));
      // Progressive: the first 64 and the next block of 64 on their own.
      CHECK(isZeroNet(slotPoints(5, 256, 7 * pixel, 2 * pixel, slot, 0, 64)));
      CHECK(isZeroNet(slotPoints(5, 256, 7 * pixel, 2 * pixel, slot, 64, 64)));
    }
  // A 1D slot: 256 values, one in each 1/256 interval.
  SamplerTile tile(5, 256, 1, 1);
  PixelSampler sampler(tile, 1, 1);
  std::vector<int> counts(256, 0);
  for (uint32_t i = 0; i < 256; ++i) {
    sampler.startSample(i);
    sampler.next2D();
    ++counts[size_t(sampler.next1D() * 256.0f)];
  }
  CHECK(std::count(counts.begin(), counts.end(), 1) == 256);
}

TEST_CASE("sampler: the samples of every aligned block of pixels form a (0,m,2)-net", "[pathtrace][sampler]") {
  for (int slot = 0; slot < 5; ++slot) {
    INFO("slot " << slot);
    // 4 x 4 pixels x 4 samples: 64 points, one in each elementary interval of area 1/64.
    CHECK(isZeroNet(blockPoints(9, 4, 0, 0, 4, slot)));
    CHECK(isZeroNet(blockPoints(9, 4, 36, 12, 4, slot)));
    CHECK(isZeroNet(blockPoints(9, 4, 64 + 20, 128 + 4, 4, slot)));  // in another tile
    // 2 x 2 pixels x 16 samples, 8 x 8 pixels x 1 sample, 16 x 16 pixels x 2 samples.
    CHECK(isZeroNet(blockPoints(3, 16, 10, 6, 2, slot)));
    CHECK(isZeroNet(blockPoints(3, 1, 8, 48, 8, slot)));
    CHECK(isZeroNet(blockPoints(3, 2, 16, 32, 16, slot)));
    // 3 samples a pixel: a pixel takes 3 of its block of 4 indices, so a
    // block's points are part of a net (at most one per interval of 1/64).
    CHECK(mostInAnInterval(blockPoints(3, 3, 4, 4, 4, slot), 6) == 1);
  }
  // A block not aligned to the Morton order is no net: it mixes points of
  // different aligned blocks (the property is the order's, not chance).
  int netsOffGrid = 0;
  for (int slot = 0; slot < 5; ++slot) netsOffGrid += isZeroNet(blockPoints(9, 4, 2, 2, 4, slot));
  CHECK(netsOffGrid < 5);
  // Across a tile's edge the blocks are independent: no net either.
  int netsAcrossTiles = 0;
  for (int slot = 0; slot < 5; ++slot) netsAcrossTiles += isZeroNet(blockPoints(9, 4, 62, 0, 4, slot));
  CHECK(netsAcrossTiles < 5);
}

TEST_CASE("sampler: a smooth 2D integral converges much faster than with random points", "[pathtrace][sampler]") {
  constexpr uint32_t kSamples = 256;
  constexpr uint32_t kPixels = 64;
  Rng rng(11, 3);
  double sobolError = 0, randomError = 0;
  for (uint32_t pixel = 0; pixel < kPixels; ++pixel) {
    double sobolSum = 0, randomSum = 0;
    for (const Vec2f& p : slotPoints(3, kSamples, pixel, 5, 0, 0, kSamples)) {
      sobolSum += smooth(p.x(), p.y());
      randomSum += smooth(rng.uniform01(), rng.uniform01());
    }
    sobolError += std::abs(sobolSum / kSamples - kSmoothIntegral);
    randomError += std::abs(randomSum / kSamples - kSmoothIntegral);
  }
  INFO("mean absolute error: scrambled Sobol " << sobolError / kPixels << ", random " << randomError / kPixels);
  CHECK(sobolError < randomError / 3.0);
}

TEST_CASE("sampler: neighbouring pixels' errors cancel in block means (blue noise)", "[pathtrace][sampler]") {
  // 4 samples a pixel over a 64 x 64 tile: each pixel's error is as large as
  // with independent streams, but the means of aligned 8 x 8 blocks (256
  // points, one net) have far smaller errors than 64 independent pixels'
  // means would (their error's rms / 8).
  constexpr uint32_t kSide = 64, kBlock = 8, kSpp = 4;
  const std::vector<double> error = pixelErrors(17, kSpp, kSide, kSide);
  double pixelSquares = 0;
  for (double e : error) pixelSquares += e * e;
  const double pixelRms = std::sqrt(pixelSquares / double(error.size()));
  double blockSquares = 0;
  for (uint32_t by = 0; by < kSide; by += kBlock)
    for (uint32_t bx = 0; bx < kSide; bx += kBlock) {
      double sum = 0;
      for (uint32_t y = by; y < by + kBlock; ++y)
        for (uint32_t x = bx; x < bx + kBlock; ++x) sum += error[y * kSide + x];
      blockSquares += (sum / (kBlock * kBlock)) * (sum / (kBlock * kBlock));
    }
  const double blockRms = std::sqrt(blockSquares / double((kSide / kBlock) * (kSide / kBlock)));
  INFO("pixel error rms " << pixelRms << ", 8 x 8 block mean's " << blockRms << " (independent pixels: "
                          << pixelRms / kBlock << ")");
  CHECK(blockRms < pixelRms / kBlock / 4);
  // In one 2 x 2 quad, pixels' errors are anti-correlated, and alike side
  // by side, one above the other and diagonally: the quads' sub-blocks are
  // handed out by all 24 permutations (a nested base-2 scramble alone pairs
  // the quad's rows up: -0.43 side by side, -0.22 one above the other).
  std::vector<double> topLeft, topRight, bottomLeft, bottomRight;
  for (uint32_t y = 0; y < kSide; y += 2)
    for (uint32_t x = 0; x < kSide; x += 2) {
      topLeft.push_back(error[y * kSide + x]), topRight.push_back(error[y * kSide + x + 1]);
      bottomLeft.push_back(error[(y + 1) * kSide + x]), bottomRight.push_back(error[(y + 1) * kSide + x + 1]);
    }
  const double across = correlation(topLeft, topRight), down = correlation(topLeft, bottomLeft),
               diagonal = correlation(topLeft, bottomRight);
  INFO("quads' correlation: across " << across << ", down " << down << ", diagonal " << diagonal);
  CHECK(across < -0.1);
  CHECK(down < -0.1);
  CHECK(diagonal < -0.1);
  CHECK(std::abs(across - down) < 0.1);
}

TEST_CASE("sampler: tiles, frames and slots are decorrelated", "[pathtrace][sampler]") {
  // The same pixel of many tiles (and the same pixel of two frames): errors
  // independent (|r| within a few times 1/sqrt(n) of 0), and pixels either
  // side of a tile's edge too.
  constexpr uint32_t kTiles = 400;
  std::vector<double> here, next, otherFrame, edgeLeft, edgeRight;
  auto error = [](uint64_t seed, uint32_t x, uint32_t y) {
    double sum = 0;
    for (const Vec2f& p : slotPoints(seed, 4, x, y, 1, 0, 4)) sum += smooth(p.x(), p.y());
    return sum / 4 - kSmoothIntegral;
  };
  for (uint32_t t = 0; t < kTiles; ++t) {
    const uint32_t x = 64 * (t % 20) + 5, y = 64 * (t / 20) + 9;
    here.push_back(error(21, x, y));
    next.push_back(error(21, x + 64, y));
    otherFrame.push_back(error(22, x, y));
    edgeLeft.push_back(error(21, x + 58, y));
    edgeRight.push_back(error(21, x + 59, y));
  }
  INFO("correlation: next tile " << correlation(here, next) << ", next frame " << correlation(here, otherFrame)
                                 << ", across a tile's edge " << correlation(edgeLeft, edgeRight));
  CHECK(std::abs(correlation(here, next)) < 0.15);
  CHECK(std::abs(correlation(here, otherFrame)) < 0.15);
  CHECK(std::abs(correlation(edgeLeft, edgeRight)) < 0.15);

  // Slots of one pixel, and of one block: the first coordinates of slot 0
  // and slot 1 over 256 samples are independent (mean r^2 near 1/256, as
  // for random pairs), not the same net twice.
  double pixelR2 = 0, blockR2 = 0;
  constexpr int kPixels = 64;
  for (uint32_t pixel = 0; pixel < kPixels; ++pixel) {
    const std::vector<Vec2f> p0 = slotPoints(9, 256, pixel, 0, 0, 0, 256), p1 = slotPoints(9, 256, pixel, 0, 1, 0, 256);
    const std::vector<Vec2f> b0 = blockPoints(9, 16, 4 * pixel, 0, 4, 0), b1 = blockPoints(9, 16, 4 * pixel, 0, 4, 1);
    std::vector<double> x0, x1, bx0, bx1;
    for (size_t i = 0; i < p0.size(); ++i) x0.push_back(p0[i].x()), x1.push_back(p1[i].x());
    for (size_t i = 0; i < b0.size(); ++i) bx0.push_back(b0[i].x()), bx1.push_back(b1[i].x());
    pixelR2 += correlation(x0, x1) * correlation(x0, x1) / kPixels;
    blockR2 += correlation(bx0, bx1) * correlation(bx0, bx1) / kPixels;
  }
  INFO("mean r^2 of slots 0 and 1: in a pixel " << pixelR2 << ", in a 4 x 4 block " << blockR2);
  CHECK(pixelR2 < 3.0 / 256.0);
  CHECK(blockR2 < 3.0 / 256.0);
}

TEST_CASE("sampler: the streams' numbers are pinned (the GPU tracer's GLSL port draws the same)",
          "[pathtrace][sampler]") {
  // An FNV-1a hash of the bits of mixed 1D and 2D draws, 60 slots a sample
  // (beyond the cached slots), jumps in the sample index, pixels of several
  // tiles, three frame seeds, three sample counts. A change here changes
  // every path-traced frame and must be made in gpu/shaders/pt_common.glsl
  // too.
  uint64_t hash = 0xcbf29ce484222325ull;
  auto add = [&hash](float v) {
    uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int k = 0; k < 4; ++k) hash = (hash ^ ((bits >> (8 * k)) & 0xffu)) * 0x100000001b3ull;
  };
  for (uint32_t spp : {70u * 977u, 70u, 1u << 26})
    for (uint64_t seed : {uint64_t{0}, uint64_t{10}, uint64_t{0xfedcba9876543210ull}})
      for (uint32_t y = 0; y < 5; ++y)
        for (uint32_t x = 0; x < 5; ++x) {
          SamplerTile tile(seed, spp, x * 37, y * 101);
          PixelSampler sampler(tile, x * 37, y * 101);
          for (uint32_t i = 0; i < 70; ++i) {
            sampler.startSample(spp == 70 ? i : i * (i % 7 == 6 ? 977u : 1u));
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
  CHECK(hash == 0x62bc7ff8fbe7c054ull);
}
