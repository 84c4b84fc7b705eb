#include "render/pathtrace/denoiser.h"

#include <algorithm>
#include <barrier>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>

namespace sdg {
namespace {

// The B3 spline, the à-trous kernel of the paper.
constexpr float kKernel[5] = {1.0f / 16.0f, 1.0f / 4.0f, 3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f};
constexpr float kMinAlbedo = 1e-3f;
// The depth tolerance for a plane facing the camera, relative to depth.
constexpr float kRelativeDepthTolerance = 1e-3f;
constexpr float kInfinity = std::numeric_limits<float>::infinity();
// Taps 2^15 pixels apart already leave any image.
constexpr int kMaxIterations = 16;

float demodulationDivisor(float albedo) { return albedo >= kMinAlbedo ? albedo : 1.0f; }

// Of the backward and forward differences, the one of smaller magnitude: at
// a depth step it is the one that stays on p's surface. 0 where neither is
// finite (a lone pixel on the background).
float gentlerDifference(float backward, float forward) {
  const auto magnitude = [](float d) { return std::isfinite(d) ? std::abs(d) : kInfinity; };
  const float chosen = magnitude(backward) <= magnitude(forward) ? backward : forward;
  return std::isfinite(chosen) ? chosen : 0.0f;
}

float luminance(const float* c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; }

bool hasSurface(const DenoiseInputs& in, size_t p) {
  const float* n = in.normal + 3 * p;
  return std::isfinite(in.depth[p]) && (n[0] != 0.0f || n[1] != 0.0f || n[2] != 0.0f);
}

}  // namespace

Denoiser::Denoiser(DenoiseSettings settings) : settings_(settings) {
  if (settings.iterations < 0 || settings.iterations > kMaxIterations)
    throw std::invalid_argument("Denoiser: iterations must be 0 to " + std::to_string(kMaxIterations));
}

void Denoiser::run(const DenoiseInputs& in, float* out) {
  if (in.width < 0 || in.height < 0) throw std::invalid_argument("Denoiser: negative image size");
  if (!in.radiance || !in.albedo || !in.normal || !in.depth || !out)
    throw std::invalid_argument("Denoiser: radiance, albedo, normal, depth and output are required");
  const size_t pixels = size_t(in.width) * size_t(in.height);
  if (pixels == 0) return;
  illuminationA_.resize(3 * pixels);
  illuminationB_.resize(3 * pixels);
  depthGradient_.resize(2 * pixels);
  noise_.resize(pixels);
  if (in.variance) {
    pixelVariance_.resize(pixels);
    varianceA_.resize(pixels);
    varianceB_.resize(pixels);
    guide_.resize(pixels);
  }

  const unsigned wanted =
      settings_.threads != 0 ? settings_.threads : std::max(1u, std::thread::hardware_concurrency());
  const unsigned threads = std::min(wanted, unsigned(in.height));
  // Each thread owns a band of rows; `sync` waits for every band between
  // the passes, since a pass reads rows up to 2 * 2^i away.
  const auto work = [&](unsigned thread, auto&& sync) {
    const int rowBegin = int(int64_t(in.height) * thread / threads);
    const int rowEnd = int(int64_t(in.height) * (thread + 1) / threads);
    prepareRows(in, rowBegin, rowEnd);
    sync();
    estimateNoiseRows(in, rowBegin, rowEnd);
    sync();
    float* source = illuminationA_.data();
    float* target = illuminationB_.data();
    float* varianceSource = in.variance ? varianceA_.data() : nullptr;
    float* varianceTarget = in.variance ? varianceB_.data() : nullptr;
    for (int iteration = 0; iteration < settings_.iterations; ++iteration) {
      filterRows(in, iteration, source, target, varianceSource, varianceTarget, rowBegin, rowEnd);
      sync();
      std::swap(source, target);
      std::swap(varianceSource, varianceTarget);
    }
    remodulateRows(in, source, out, rowBegin, rowEnd);
  };
  if (threads == 1) {
    work(0, [] {});
    return;
  }
  std::barrier barrier{static_cast<std::ptrdiff_t>(threads)};
  const auto sync = [&barrier] { barrier.arrive_and_wait(); };
  std::vector<std::jthread> helpers;
  helpers.reserve(threads - 1);
  for (unsigned t = 1; t < threads; ++t) helpers.emplace_back([&work, &sync, t] { work(t, sync); });
  work(0, sync);
}

// Demodulated illumination and the depth gradient of rows [rowBegin, rowEnd).
void Denoiser::prepareRows(const DenoiseInputs& in, int rowBegin, int rowEnd) {
  const int w = in.width, h = in.height;
  for (int y = rowBegin; y < rowEnd; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * size_t(w) + size_t(x);
      for (size_t c = 3 * p; c < 3 * p + 3; ++c) illuminationA_[c] = in.radiance[c] / demodulationDivisor(in.albedo[c]);
      if (in.variance) {
        // Demodulation scales the luminance by about its ratio here; where
        // the radiance is black, by the divisors' luminance.
        const float radianceL = luminance(in.radiance + 3 * p), illuminationL = luminance(illuminationA_.data() + 3 * p);
        const float divisors[3] = {demodulationDivisor(in.albedo[3 * p]), demodulationDivisor(in.albedo[3 * p + 1]),
                                   demodulationDivisor(in.albedo[3 * p + 2])};
        const float scale = radianceL > 0.0f ? illuminationL / radianceL : 1.0f / luminance(divisors);
        pixelVariance_[p] = in.variance[p] * scale * scale;
      }
      const float z = in.depth[p];
      depthGradient_[2 * p] = gentlerDifference(x > 0 ? z - in.depth[p - 1] : kInfinity,
                                                x + 1 < w ? in.depth[p + 1] - z : kInfinity);
      depthGradient_[2 * p + 1] = gentlerDifference(y > 0 ? z - in.depth[p - size_t(w)] : kInfinity,
                                                    y + 1 < h ? in.depth[p + size_t(w)] - z : kInfinity);
    }
}

// The standard deviation of the demodulated luminance over each pixel's
// 5 x 5 neighbourhood on the same instance: SVGF's spatial variance
// estimate, which a single frame without per-pixel sample variance has.
void Denoiser::estimateNoiseRows(const DenoiseInputs& in, int rowBegin, int rowEnd) {
  const int w = in.width, h = in.height;
  if (in.variance) {
    // SVGF: the per-pixel variance blurred by a 3 x 3 Gaussian on the
    // pixel's instance (a 4-sample variance alone is itself very noisy).
    constexpr float kGauss[3] = {0.25f, 0.5f, 0.25f};
    for (int y = rowBegin; y < rowEnd; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t p = size_t(y) * size_t(w) + size_t(x);
        float sum = 0.0f, guide = 0.0f, weights = 0.0f;
        for (int qy = std::max(0, y - 1); qy <= std::min(h - 1, y + 1); ++qy)
          for (int qx = std::max(0, x - 1); qx <= std::min(w - 1, x + 1); ++qx) {
            const size_t q = size_t(qy) * size_t(w) + size_t(qx);
            if (q != p && (!hasSurface(in, q) || (in.instance && in.instance[q] != in.instance[p]))) continue;
            const float weight = kGauss[qx - x + 1] * kGauss[qy - y + 1];
            sum += weight * pixelVariance_[q];
            guide += weight * luminance(illuminationA_.data() + 3 * q);
            weights += weight;
          }
        varianceA_[p] = sum / weights;
        guide_[p] = guide / weights;
      }
    return;
  }
  for (int y = rowBegin; y < rowEnd; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * size_t(w) + size_t(x);
      double sum = 0, sum2 = 0;
      int n = 0;
      for (int qy = std::max(0, y - 2); qy <= std::min(h - 1, y + 2); ++qy)
        for (int qx = std::max(0, x - 2); qx <= std::min(w - 1, x + 2); ++qx) {
          const size_t q = size_t(qy) * size_t(w) + size_t(qx);
          if (!hasSurface(in, q) || (in.instance && in.instance[q] != in.instance[p])) continue;
          const double l = luminance(illuminationA_.data() + 3 * q);
          sum += l;
          sum2 += l * l;
          ++n;
        }
      noise_[p] = n > 1 ? float(std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)))) : 0.0f;
    }
}

void Denoiser::filterRows(const DenoiseInputs& in, int iteration, const float* source, float* target,
                          const float* varianceSource, float* varianceTarget, int rowBegin, int rowEnd) const {
  const int w = in.width, h = in.height;
  const int step = 1 << iteration;
  // Without a carried variance each pass is assumed to leave half the
  // noise's variance: the scale shrinks with it.
  const float sigmaColor =
      varianceSource ? settings_.sigmaColor : settings_.sigmaColor * std::pow(0.5f, 0.5f * float(iteration));
  for (int y = rowBegin; y < rowEnd; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * size_t(w) + size_t(x);
      const float* cp = source + 3 * p;
      if (!hasSurface(in, p)) {
        std::copy(cp, cp + 3, target + 3 * p);
        if (varianceSource) varianceTarget[p] = varianceSource[p];
        continue;
      }
      const float* np = in.normal + 3 * p;
      const float zp = in.depth[p];
      const float gx = depthGradient_[2 * p], gy = depthGradient_[2 * p + 1];
      // The first pass compares the pixels' 3 x 3 means, not their single
      // noisy values: weights that favour values near a noisy centre pull
      // skewed path-tracing noise (rare bright samples) toward its mode,
      // darkening the image; later passes see filtered values already.
      const bool guided = varianceSource && iteration == 0;
      const float luminanceP = guided ? guide_[p] : luminance(cp);
      // A floor of 1 % of the pixel's own level, so noise-free regions
      // still stop at real edges instead of dividing by zero.
      const float noise = varianceSource ? std::sqrt(varianceSource[p]) : noise_[p];
      const float colorScale = sigmaColor * noise + 0.01f * std::abs(luminanceP) + 1e-6f;
      float sum[3] = {0.0f, 0.0f, 0.0f};
      float weightSum = 0.0f, varianceSum = 0.0f;
      for (int ky = -2; ky <= 2; ++ky) {
        const int qy = y + ky * step;
        if (qy < 0 || qy >= h) continue;
        for (int kx = -2; kx <= 2; ++kx) {
          const int qx = x + kx * step;
          if (qx < 0 || qx >= w) continue;
          const size_t q = size_t(qy) * size_t(w) + size_t(qx);
          const float* cq = source + 3 * q;
          float weight = kKernel[kx + 2] * kKernel[ky + 2];
          if (q != p) {
            if (in.instance && in.instance[q] != in.instance[p]) continue;
            const float* nq = in.normal + 3 * q;
            const float cosine = np[0] * nq[0] + np[1] * nq[1] + np[2] * nq[2];
            const float dz = std::abs(in.depth[q] - zp);
            if (!(cosine > 0.0f) || !std::isfinite(dz)) continue;
            const float expectedDz = std::abs(gx * float(qx - x) + gy * float(qy - y));
            const float depthScale = settings_.sigmaDepth * expectedDz + kRelativeDepthTolerance * std::abs(zp);
            const float colorDistance = std::abs((guided ? guide_[q] : luminance(cq)) - luminanceP);
            weight *= std::pow(cosine, settings_.sigmaNormal) *
                      std::exp(-dz / std::max(depthScale, std::numeric_limits<float>::min())) *
                      std::exp(-colorDistance / colorScale);
          }
          for (int c = 0; c < 3; ++c) sum[c] += weight * cq[c];
          weightSum += weight;
          if (varianceSource) varianceSum += weight * weight * varianceSource[q];
        }
      }
      for (int c = 0; c < 3; ++c) target[3 * p + size_t(c)] = sum[c] / weightSum;
      if (varianceSource) varianceTarget[p] = varianceSum / (weightSum * weightSum);
    }
}

void Denoiser::remodulateRows(const DenoiseInputs& in, const float* source, float* out, int rowBegin,
                              int rowEnd) const {
  const size_t begin = 3 * size_t(rowBegin) * size_t(in.width), end = 3 * size_t(rowEnd) * size_t(in.width);
  for (size_t i = begin; i < end; ++i) out[i] = source[i] * demodulationDivisor(in.albedo[i]);
}

}  // namespace sdg
