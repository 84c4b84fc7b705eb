// The path tracer's edge-avoiding à-trous denoiser (Dammertz et al. 2010,
// doubly stochastic weights): noise falls and the mean stays, light is
// neither lost nor gained (exactly, per region, and on skewed path-tracing
// noise, in expectation, also on a rendered Cornell box), edges between
// instances, normals and depths stay sharp, albedo texture survives, and
// the output does not depend on the thread count.
#include <catch2/catch.hpp>

#include <cmath>
#include <array>
#include <cstring>
#include <map>
#include <limits>
#include <vector>

#include "behavior/rng.h"
#include "pt_test_scenes.h"
#include "render/pathtrace/denoiser.h"

using namespace sdg;

namespace {

// A frame's planes, filled per pixel by the tests.
struct Frame {
  int width, height;
  std::vector<float> radiance, albedo, normal, depth;
  std::vector<uint32_t> instance;
  std::vector<float> variance;  // per pixel, the tracer's; empty: the spatial estimate

  Frame(int w, int h)
      : width(w), height(h), radiance(size_t(w * h * 3), 0.0f), albedo(size_t(w * h * 3), 1.0f),
        normal(size_t(w * h * 3), 0.0f), depth(size_t(w * h), 2.0f), instance(size_t(w * h), 1) {
    for (size_t p = 0; p < size_t(w * h); ++p) normal[3 * p + 2] = 1.0f;
  }
  size_t at(int x, int y) const { return size_t(y) * size_t(width) + size_t(x); }
  void setRgb(std::vector<float>& plane, int x, int y, float r, float g, float b) {
    float* v = plane.data() + 3 * at(x, y);
    v[0] = r, v[1] = g, v[2] = b;
  }
  DenoiseInputs inputs(bool withInstances = true) const {
    return {width, height, radiance.data(), albedo.data(), normal.data(), depth.data(),
            withInstances ? instance.data() : nullptr, variance.empty() ? nullptr : variance.data()};
  }
};

std::vector<float> denoise(const Frame& frame, bool withInstances = true, unsigned threads = 1) {
  std::vector<float> out(frame.radiance.size());
  Denoiser({.threads = threads}).run(frame.inputs(withInstances), out.data());
  return out;
}

// Roughly Gaussian noise of unit variance: the sum of four uniforms.
float gaussianish(Rng& rng) {
  double sum = 0;
  for (int i = 0; i < 4; ++i) sum += rng.uniform01();
  return float((sum - 2.0) * std::sqrt(3.0));
}

double rmsError(const std::vector<float>& image, float truth) {
  double sum = 0;
  for (float v : image) sum += double(v - truth) * double(v - truth);
  return std::sqrt(sum / double(image.size()));
}

// The error of 16 x 16-pixel block means over the truth's sum, from the
// per-pixel sums over several frames of (denoised - noisy) and of the
// truth (or of the noisy frames: its expectation). Since the noisy frame
// is unbiased, E[denoised - noisy] is the denoiser's bias, and the paired
// difference carries far less noise than denoised - truth would (the
// noise that the filter leaves in place cancels): no many-sample
// reference is needed to resolve 1 %.
double pairedBlockBias(const std::vector<double>& differenceSum, const std::vector<double>& truthSum, int width,
                       int height) {
  constexpr int kBlock = 16;
  double error = 0, total = 0;
  for (int by = 0; by + kBlock <= height; by += kBlock)
    for (int bx = 0; bx + kBlock <= width; bx += kBlock)
      for (int c = 0; c < 3; ++c) {
        double difference = 0;
        for (int y = by; y < by + kBlock; ++y)
          for (int x = bx; x < bx + kBlock; ++x) {
            const size_t i = 3 * (size_t(y) * size_t(width) + size_t(x)) + size_t(c);
            difference += differenceSum[i];
            total += truthSum[i];
          }
        error += std::abs(difference);
      }
  return error / total;
}

double mean(const std::vector<float>& image) {
  double sum = 0;
  for (float v : image) sum += v;
  return sum / double(image.size());
}

// An irregular frame: noise, several instances, slanted depth, a few
// pixels of background, a size no thread count divides evenly.
Frame irregularFrame() {
  Frame frame(97, 61);
  Rng rng(6, 6);
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x) {
      const size_t p = frame.at(x, y);
      frame.instance[p] = uint32_t((x / 20) + 3 * (y / 25));
      frame.depth[p] = 1.0f + 0.01f * float(x) + 0.003f * float(y);
      frame.setRgb(frame.albedo, x, y, float(rng.uniform01()), 0.5f, 0.25f);
      frame.setRgb(frame.radiance, x, y, float(rng.uniform01()), float(rng.uniform01()), 2.0f * float(rng.uniform01()));
      if (rng.uniform01() < 0.02) frame.depth[p] = std::numeric_limits<float>::infinity();
    }
  return frame;
}

// A per-pixel variance uniform in [0, scale); none (the spatial estimate)
// for scale 0.
void randomVariance(Frame& frame, float scale, Rng& rng) {
  frame.variance.clear();
  if (scale > 0.0f)
    for (size_t p = 0; p < frame.depth.size(); ++p) frame.variance.push_back(scale * float(rng.uniform01()));
}

}  // namespace

TEST_CASE("denoiser: a noisy flat wall converges toward its mean, which stays", "[pathtrace][denoiser]") {
  constexpr float kTruth = 0.4f;
  Frame wall(64, 64);
  Rng rng(1, 1);
  for (size_t i = 0; i < wall.radiance.size(); ++i) {
    wall.albedo[i] = 0.5f;
    wall.radiance[i] = kTruth * (1.0f + 0.3f * gaussianish(rng));
  }
  for (bool perPixel : {false, true}) {
    INFO((perPixel ? "per-pixel variance" : "spatial noise estimate"));
    // The radiance's luminance variance per pixel, as the tracer reports it.
    if (perPixel) wall.variance.assign(size_t(64 * 64), (0.3f * kTruth) * (0.3f * kTruth));
    const std::vector<float> out = denoise(wall);
    const double before = rmsError(wall.radiance, kTruth), after = rmsError(out, kTruth);
    INFO("RMS error " << before << " -> " << after);
    CHECK(after * 4.0 < before);
    CHECK(mean(out) == Approx(mean(wall.radiance)).epsilon(0.005));
  }
}

TEST_CASE("denoiser: an edge between instances stays sharp", "[pathtrace][denoiser]") {
  // Left: instance 1 at 0.2; right: instance 2 at 1.0; the same wall
  // otherwise, with 10 % noise.
  Frame frame(64, 32);
  Rng rng(2, 2);
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x) {
      const bool right = x >= 32;
      frame.instance[frame.at(x, y)] = right ? 2 : 1;
      for (int c = 0; c < 3; ++c)
        frame.radiance[3 * frame.at(x, y) + size_t(c)] = (right ? 1.0f : 0.2f) * (1.0f + 0.1f * gaussianish(rng));
    }
  const std::vector<float> out = denoise(frame);
  double leftColumn = 0, rightColumn = 0;
  for (int y = 0; y < frame.height; ++y) {
    const float left = out[3 * frame.at(31, y)], right = out[3 * frame.at(32, y)];
    CHECK(left == Approx(0.2f).epsilon(0.05));
    CHECK(right == Approx(1.0f).epsilon(0.05));
    leftColumn += left / frame.height, rightColumn += right / frame.height;
  }
  CHECK(leftColumn == Approx(0.2).epsilon(0.02));
  CHECK(rightColumn == Approx(1.0).epsilon(0.02));
  // The ids are what holds it: without them the colour weight alone lets
  // the bright side bleed into the dark one.
  const std::vector<float> blended = denoise(frame, false);
  double bledColumn = 0;
  for (int y = 0; y < frame.height; ++y) bledColumn += blended[3 * frame.at(31, y)] / frame.height;
  CHECK(bledColumn > 0.2 * 1.05);
}

TEST_CASE("denoiser: normal and depth edges stay sharp within one instance", "[pathtrace][denoiser]") {
  // Radiance 0.5 and 0.7 on either side: close enough that the colour
  // weight alone would blend them.
  Frame frame(64, 64);
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x) {
      const bool otherWall = x >= 32;       // a wall at a right angle
      const bool inFront = y >= 32 && !otherWall;  // a box one unit closer
      const float value = (otherWall || inFront) ? 0.7f : 0.5f;
      frame.setRgb(frame.radiance, x, y, value, value, value);
      if (otherWall) frame.setRgb(frame.normal, x, y, 1.0f, 0.0f, 0.0f);
      if (inFront) frame.depth[frame.at(x, y)] = 1.0f;
    }
  const std::vector<float> out = denoise(frame);
  for (int y = 0; y < frame.height; ++y) {
    CHECK(out[3 * frame.at(31, y)] == Approx(y >= 32 ? 0.7f : 0.5f).epsilon(0.01));
    CHECK(out[3 * frame.at(32, y)] == Approx(0.7f).epsilon(0.01));
  }
  for (int x = 0; x < 32; ++x) {
    CHECK(out[3 * frame.at(x, 31)] == Approx(0.5f).epsilon(0.01));
    CHECK(out[3 * frame.at(x, 32)] == Approx(0.7f).epsilon(0.01));
  }
}

TEST_CASE("denoiser: a checkerboard albedo under uniform light survives (demodulation)", "[pathtrace][denoiser]") {
  // 2 x 2-pixel checks of albedo 0.1 and 0.9, lit by irradiance 0.8, with
  // 20 % noise: the filter smooths the light, the albedo puts the texture back.
  constexpr float kLight = 0.8f;
  Frame frame(64, 64);
  Rng rng(4, 4);
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x) {
      const float a = ((x / 2 + y / 2) % 2 == 0) ? 0.1f : 0.9f;
      frame.setRgb(frame.albedo, x, y, a, a, a);
      for (int c = 0; c < 3; ++c)
        frame.radiance[3 * frame.at(x, y) + size_t(c)] = a * kLight * (1.0f + 0.2f * gaussianish(rng));
    }
  for (bool perPixel : {false, true}) {
    INFO((perPixel ? "per-pixel variance" : "spatial noise estimate"));
    frame.variance.clear();
    // The luminance of independent 20 % noise per channel.
    constexpr float kLuminanceShare = 0.2126f * 0.2126f + 0.7152f * 0.7152f + 0.0722f * 0.0722f;
    if (perPixel)
      for (size_t p = 0; p < frame.depth.size(); ++p)
        frame.variance.push_back(kLuminanceShare * std::pow(0.2f * frame.albedo[3 * p] * kLight, 2.0f));
    const std::vector<float> out = denoise(frame);
    double noisyError = 0, denoisedError = 0, worst = 0;
    for (size_t i = 0; i < out.size(); ++i) {
      const float truth = frame.albedo[i] * kLight;
      noisyError += std::abs(frame.radiance[i] - truth) / truth;
      denoisedError += std::abs(out[i] - truth) / truth;
      worst = std::max(worst, double(std::abs(out[i] - truth) / truth));
    }
    INFO("mean error " << noisyError / double(out.size()) << " -> " << denoisedError / double(out.size())
                       << ", the worst pixel " << worst);
    CHECK(denoisedError * 10.0 < noisyError);
    // A lone outlier keeps more of its own value than under a normalised
    // filter (the filter keeps its light rather than dropping it), so the
    // tail is somewhat wider than the mean.
    CHECK(worst < 0.15);
  }
}

TEST_CASE("denoiser: pixels without a surface keep their radiance", "[pathtrace][denoiser]") {
  Frame frame(16, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const bool sky = y < 8;
      const float v = sky ? 2.0f + 0.1f * float(x) : 0.3f;
      frame.setRgb(frame.radiance, x, y, v, v, v);
      if (sky) {
        frame.setRgb(frame.normal, x, y, 0.0f, 0.0f, 0.0f);
        frame.setRgb(frame.albedo, x, y, 0.0f, 0.0f, 0.0f);
        frame.depth[frame.at(x, y)] = std::numeric_limits<float>::infinity();
      }
    }
  const std::vector<float> out = denoise(frame);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const float value = out[3 * frame.at(x, y)];
      if (y < 8)
        CHECK(value == frame.radiance[3 * frame.at(x, y)]);
      else
        CHECK(value == Approx(0.3f).epsilon(1e-5));
    }
}

TEST_CASE("denoiser: the output is the same whatever the thread count", "[pathtrace][denoiser]") {
  Frame frame = irregularFrame();
  Rng rng(6, 6);
  for (bool perPixel : {true, false}) {
    INFO((perPixel ? "per-pixel variance" : "spatial noise estimate"));
    randomVariance(frame, perPixel ? 0.05f : 0.0f, rng);
    const std::vector<float> single = denoise(frame, true, 1);
    for (unsigned threads : {2u, 3u, 8u, 61u, 200u}) {
      INFO(threads << " threads");
      const std::vector<float> multi = denoise(frame, true, threads);
      CHECK(std::memcmp(single.data(), multi.data(), single.size() * sizeof(float)) == 0);
    }
  }
  const std::vector<float> single = denoise(frame, true, 1);
  // One denoiser, reused at another size and back: its scratch buffers
  // carry nothing over.
  Denoiser reused({.threads = 4});
  std::vector<float> out(single.size());
  Frame small(5, 3);
  std::vector<float> smallOut(small.radiance.size());
  reused.run(small.inputs(), smallOut.data());
  reused.run(frame.inputs(), out.data());
  CHECK(std::memcmp(single.data(), out.data(), single.size() * sizeof(float)) == 0);
  for (float v : out) CHECK(std::isfinite(v));
}

TEST_CASE("denoiser: each region that edges close keeps its light exactly", "[pathtrace][denoiser]") {
  // The filter moves illumination (radiance over albedo) within an
  // instance, but its sum over the instance stays, whatever the noise
  // estimate; background pixels keep theirs.
  Frame frame = irregularFrame();
  Rng rng(7, 7);
  for (bool perPixel : {false, true}) {
    INFO((perPixel ? "per-pixel variance" : "spatial noise estimate"));
    randomVariance(frame, perPixel ? 0.5f : 0.0f, rng);
    const std::vector<float> out = denoise(frame);
    // It did smooth: the differences between neighbours fall (green, whose
    // albedo is uniform).
    double before = 0, after = 0;
    for (size_t i = 4; i < out.size(); i += 3) {
      before += std::abs(frame.radiance[i] - frame.radiance[i - 3]);
      after += std::abs(out[i] - out[i - 3]);
    }
    CHECK(after < 0.5 * before);
    std::map<uint32_t, std::array<double, 2>> sums;  // per instance: before, after
    for (size_t i = 0; i < out.size(); ++i) {
      const float divisor = frame.albedo[i] >= 1e-3f ? frame.albedo[i] : 1.0f;
      sums[frame.instance[i / 3]][0] += frame.radiance[i] / divisor;
      sums[frame.instance[i / 3]][1] += out[i] / divisor;
    }
    for (const auto& [id, sum] : sums) {
      INFO("instance " << id);
      CHECK(sum[1] == Approx(sum[0]).epsilon(1e-5));
    }
  }
}

TEST_CASE("denoiser: skewed noise (rare bright samples) is not darkened", "[pathtrace][denoiser]") {
  // Path-tracing noise at 4 samples: most samples well below the mean, a
  // few far above it. A wall lit by a gradient; each pixel
  // the mean of 4 samples, with the variance of that mean as the tracer
  // reports it. A filter whose colour weights reject the bright samples
  // without keeping their light darkens the image: the former normalised
  // filter's block means were 3.4 % off here, this one's 0.5 % (light it
  // moves along the gradient at the image's borders).
  constexpr int kSize = 64, kFrames = 12, kSamples = 4;
  Frame frame(kSize, kSize);
  std::vector<double> truthSum(frame.radiance.size()), differenceSum(frame.radiance.size());
  std::vector<double> noisyChange, denoisedChange;  // between two frames, for the noise left
  std::vector<float> firstOut, firstNoisy;
  Rng rng(8, 8);
  for (int f = 0; f < kFrames; ++f) {
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const size_t p = frame.at(x, y);
        const float light = 0.4f + 0.01f * float(x) + 0.004f * float(y);
        double sum = 0, sum2 = 0;
        for (int s = 0; s < kSamples; ++s) {
          // Mean 1: 0.5 with probability 0.9, 5.5 with 0.1.
          const double sample = light * (rng.uniform01() < 0.1 ? 5.5 : 0.5);
          sum += sample, sum2 += sample * sample;
        }
        const double meanValue = sum / kSamples;
        frame.setRgb(frame.radiance, x, y, float(meanValue), float(meanValue), float(meanValue));
        frame.variance.resize(frame.depth.size());
        frame.variance[p] = float(std::max(0.0, sum2 / kSamples - meanValue * meanValue) / (kSamples - 1));
        for (int c = 0; c < 3; ++c) truthSum[3 * p + size_t(c)] += light;
      }
    const std::vector<float> out = denoise(frame);
    for (size_t i = 0; i < out.size(); ++i) differenceSum[i] += double(out[i]) - double(frame.radiance[i]);
    if (f == 0) firstOut = out, firstNoisy = frame.radiance;
    if (f == 1) {
      double noisy = 0, denoised = 0;
      for (size_t i = 0; i < out.size(); ++i) {
        noisy += std::abs(frame.radiance[i] - firstNoisy[i]);
        denoised += std::abs(out[i] - firstOut[i]);
      }
      INFO("frame-to-frame change: noisy " << noisy << ", denoised " << denoised);
      CHECK(denoised < 0.3 * noisy);
    }
  }
  const double bias = pairedBlockBias(differenceSum, truthSum, kSize, kSize);
  INFO("block bias " << 100 * bias << " %");
  CHECK(bias < 0.01);
}

TEST_CASE("denoiser: the Cornell box at 4 samples keeps its block means within 1.5 %", "[pathtrace][denoiser]") {
  // The target on the real thing (docs/performance.md measures it
  // against a 1,024-sample reference at 16 frames: about 1 %; the former
  // filter 1.7 %). Four frames, paired as above.
  constexpr int kSize = 128, kFrames = 4;
  const Scene scene = loadScene(SDG_SOURCE_DIR "/scenes/examples/cornell_box.yaml", builtinRegistry().catalog());
  const RenderList list = buildRenderList(scene.stage);
  PathTraceSettings settings;
  settings.samples = 4;
  settings.maxBounces = int(scene.render.getUInt("max_bounces"));
  settings.threads = 2;
  PathTracer tracer(pttest::testAssets(), settings);
  Denoiser denoiser{DenoiseSettings{}};
  std::vector<double> noisySum, differenceSum;
  std::vector<float> out, firstOut, firstNoisy;
  double noisyChange = 0, denoisedChange = 0;
  PathTracedFrame frame;
  for (int f = 0; f < kFrames; ++f) {
    tracer.render(list, 0, kSize, kSize, uint64_t(f), frame);
    out.resize(frame.radiance.size());
    denoiser.run({frame.width, frame.height, frame.radiance.data(), frame.albedo.data(), frame.normal.data(),
                  frame.depth.data(), frame.instance.data(), frame.variance.data()},
                 out.data());
    noisySum.resize(out.size()), differenceSum.resize(out.size());
    for (size_t i = 0; i < out.size(); ++i) {
      noisySum[i] += frame.radiance[i];
      differenceSum[i] += double(out[i]) - double(frame.radiance[i]);
    }
    if (f == 0) firstOut = out, firstNoisy = frame.radiance;
    if (f == 1)
      for (size_t i = 0; i < out.size(); ++i) {
        noisyChange += std::abs(frame.radiance[i] - firstNoisy[i]);
        denoisedChange += std::abs(out[i] - firstOut[i]);
      }
  }
  const double bias = pairedBlockBias(differenceSum, noisySum, kSize, kSize);
  INFO("block bias " << 100 * bias << " %; frame-to-frame change: noisy " << noisyChange << ", denoised "
                     << denoisedChange);
  CHECK(bias < 0.015);
  CHECK(denoisedChange < 0.3 * noisyChange);  // and it does denoise
}
