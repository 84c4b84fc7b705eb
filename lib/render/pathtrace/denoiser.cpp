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

// The 12 taps of the 5 x 5 kernel that follow the centre in reading order
// (kx, ky); the other 12 mirror them. A pair's weight is symmetric, so it
// is computed once, by the pixel the offset starts from.
constexpr int kHalfTaps = 12;
constexpr int kHalfTap[kHalfTaps][2] = {{1, 0},  {2, 0},  {-2, 1}, {-1, 1}, {0, 1}, {1, 1},
                                        {2, 1},  {-2, 2}, {-1, 2}, {0, 2},  {1, 2}, {2, 2}};

// Calls visit(q, w) for each tap q of pixel (x, y) inside the image, the
// centre left out, w its weight from the half weights: each half tap t
// forward (q = p + offset, p's weight t) then backward (q = p - offset, q's
// weight t). (The GPU kernel recomputes the weights, in reading order: the
// same sums up to rounding.)
template <class Visit>
void forEachTap(int x, int y, int w, int h, int step, const float* halfWeights, Visit&& visit) {
  const size_t p = size_t(y) * size_t(w) + size_t(x);
  for (int t = 0; t < kHalfTaps; ++t)
    for (int side = 1; side >= -1; side -= 2) {
      const int qx = x + side * kHalfTap[t][0] * step, qy = y + side * kHalfTap[t][1] * step;
      if (qx < 0 || qx >= w || qy < 0 || qy >= h) continue;
      const size_t q = size_t(qy) * size_t(w) + size_t(qx);
      visit(q, halfWeights[kHalfTaps * (side > 0 ? p : q) + size_t(t)]);
    }
}

bool hasSurface(const DenoiseInputs& in, size_t p) {
  const float* n = in.normal + 3 * p;
  return std::isfinite(in.depth[p]) && (n[0] != 0.0f || n[1] != 0.0f || n[2] != 0.0f);
}

}  // namespace

float denoisePassSigmaColor(const DenoiseSettings& settings, int iteration, bool perPixelVariance) {
  // Without a carried variance each pass is assumed to leave half the
  // noise's variance: the scale shrinks with it.
  const float noiseScale = perPixelVariance ? 1.0f : std::pow(0.5f, 0.5f * float(iteration));
  return settings.sigmaColor * noiseScale * std::pow(settings.sigmaColorDecay, float(iteration));
}

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
  noiseVariance_.resize(pixels);
  weightTotal_.resize(pixels);
  halfWeights_.resize(kHalfTaps * pixels);
  levels_.resize(2 * pixels);
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
      const PassView pass = passView(iteration, source, varianceSource);
      levelRows(in, pass, rowBegin, rowEnd);
      sync();
      weighRows(in, pass, rowBegin, rowEnd);
      sync();
      totalRows(in, pass, rowBegin, rowEnd);
      sync();
      filterRows(in, pass, target, varianceTarget, rowBegin, rowEnd);
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
      noiseVariance_[p] = n > 1 ? float(std::max(0.0, sum2 / n - (sum / n) * (sum / n))) : 0.0f;
    }
}

// The edge-stopping weight of the tap from p to q (p != q, q - p = (kx,
// ky) taps), kernel weight included; 0 for a tap that crosses an edge.
// Symmetric: every term reads p and q alike (and each pair's weight is
// computed once, for both), which makes the filter conserve light exactly
// (see filterRows).
float Denoiser::tapWeight(const DenoiseInputs& in, const PassView& pass, size_t p, size_t q, int kx, int ky) const {
  if (in.instance && in.instance[q] != in.instance[p]) return 0.0f;
  const float* np = in.normal + 3 * p;
  const float* nq = in.normal + 3 * q;
  const float cosine = np[0] * nq[0] + np[1] * nq[1] + np[2] * nq[2];
  const float zp = in.depth[p], zq = in.depth[q];
  const float dz = std::abs(zq - zp);
  if (!(cosine > 0.0f) || !std::isfinite(dz)) return 0.0f;
  // The depth change planes through p and q with their own screen-space
  // gradients would make over the offset, averaged.
  const float dx = float(kx * pass.step), dy = float(ky * pass.step);
  const float expectedDz = std::abs(depthGradient_[2 * p] * dx + depthGradient_[2 * p + 1] * dy) +
                           std::abs(depthGradient_[2 * q] * dx + depthGradient_[2 * q + 1] * dy);
  const float depthScale =
      0.5f * settings_.sigmaDepth * expectedDz + 0.5f * kRelativeDepthTolerance * (std::abs(zp) + std::abs(zq));
  // Colour: the difference over sigmaColor times the two pixels' mean noise
  // (standard deviation), with a floor of 1 % of their mean level so
  // noise-free regions still stop at real edges instead of dividing by zero.
  const float* lp = levels_.data() + 2 * p;
  const float* lq = levels_.data() + 2 * q;
  const float colorScale =
      0.5f * pass.sigmaColor * (lp[1] + lq[1]) + 0.005f * (std::abs(lp[0]) + std::abs(lq[0])) + 1e-6f;
  // The normal's, the depth's and the colour's factors in one exp.
  return kKernel[kx + 2] * kKernel[ky + 2] *
         std::exp(settings_.sigmaNormal * std::log(cosine) -
                  dz / std::max(depthScale, std::numeric_limits<float>::min()) -
                  std::abs(lq[0] - lp[0]) / colorScale);
}

Denoiser::PassView Denoiser::passView(int iteration, const float* source, const float* varianceSource) const {
  PassView view;
  view.step = 1 << iteration;
  view.source = source;
  view.variance = varianceSource ? varianceSource : noiseVariance_.data();
  // The first pass with a per-pixel variance compares the pixels' 3 x 3
  // means, not their single noisy values (see denoiser.h).
  view.guide = varianceSource && iteration == 0 ? guide_.data() : nullptr;
  view.sigmaColor = denoisePassSigmaColor(settings_, iteration, varianceSource != nullptr);
  return view;
}

// What an iteration's colour weights compare, per pixel: the luminance (or
// the guide) and the noise's standard deviation, once rather than per tap.
void Denoiser::levelRows(const DenoiseInputs& in, const PassView& pass, int rowBegin, int rowEnd) {
  const size_t begin = size_t(rowBegin) * size_t(in.width), end = size_t(rowEnd) * size_t(in.width);
  for (size_t p = begin; p < end; ++p) {
    levels_[2 * p] = pass.guide ? pass.guide[p] : luminance(pass.source + 3 * p);
    levels_[2 * p + 1] = std::sqrt(pass.variance[p]);
  }
}

// The half taps' weights of rows [rowBegin, rowEnd): 0 where the tap
// leaves the image (or crosses an edge, or either pixel has no surface).
void Denoiser::weighRows(const DenoiseInputs& in, const PassView& pass, int rowBegin, int rowEnd) {
  const int w = in.width, h = in.height;
  for (int y = rowBegin; y < rowEnd; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * size_t(w) + size_t(x);
      for (int t = 0; t < kHalfTaps; ++t) {
        const int kx = kHalfTap[t][0], ky = kHalfTap[t][1];
        const int qx = x + kx * pass.step, qy = y + ky * pass.step;
        const bool inside = qx >= 0 && qx < w && qy < h;
        halfWeights_[kHalfTaps * p + size_t(t)] =
            inside ? tapWeight(in, pass, p, size_t(qy) * size_t(w) + size_t(qx), kx, ky) : 0.0f;
      }
    }
}

// W_p: the sum of p's tap weights, its own (the kernel's centre) included.
void Denoiser::totalRows(const DenoiseInputs& in, const PassView& pass, int rowBegin, int rowEnd) {
  const int w = in.width, h = in.height;
  for (int y = rowBegin; y < rowEnd; ++y)
    for (int x = 0; x < w; ++x) {
      float total = kKernel[2] * kKernel[2];
      forEachTap(x, y, w, h, pass.step, halfWeights_.data(), [&](size_t, float weight) { total += weight; });
      weightTotal_[size_t(y) * size_t(w) + size_t(x)] = total;
    }
}

// One iteration: out_p = c_p + sum_q a_pq (c_q - c_p), a_pq = w_pq /
// max(W_p, W_q). The weights are symmetric and every row's off-centre sum
// is below 1, so the filter's matrix is doubly stochastic: a convex
// combination per pixel that also moves no light in or out of any region
// (Milanfar 2013, "Symmetrizing Smoothing Filters"). The usual normalised
// form w_pq / W_p darkens: a bright outlier q that its neighbours' colour
// weights reject gives them little, keeps little itself, and its light is
// lost (skewed path-tracing noise makes that systematic).
void Denoiser::filterRows(const DenoiseInputs& in, const PassView& pass, float* target, float* varianceTarget,
                          int rowBegin, int rowEnd) const {
  const int w = in.width, h = in.height;
  for (int y = rowBegin; y < rowEnd; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t p = size_t(y) * size_t(w) + size_t(x);
      const float* cp = pass.source + 3 * p;
      const float ownVariance = pass.variance[p];
      if (!hasSurface(in, p)) {
        std::copy(cp, cp + 3, target + 3 * p);
        if (varianceTarget) varianceTarget[p] = ownVariance;
        continue;
      }
      const float totalP = weightTotal_[p];
      float sum[3] = {0.0f, 0.0f, 0.0f};
      float weightSum = 0.0f, varianceSum = 0.0f;
      forEachTap(x, y, w, h, pass.step, halfWeights_.data(), [&](size_t q, float weight) {
        if (weight == 0.0f) return;
        const float a = weight / std::max(totalP, weightTotal_[q]);
        const float* cq = pass.source + 3 * q;
        for (int c = 0; c < 3; ++c) sum[c] += a * cq[c];
        weightSum += a;
        varianceSum += a * a * pass.variance[q];
      });
      const float own = 1.0f - weightSum;
      for (int c = 0; c < 3; ++c) target[3 * p + size_t(c)] = sum[c] + own * cp[c];
      if (varianceTarget) varianceTarget[p] = varianceSum + own * own * ownVariance;
    }
}

void Denoiser::remodulateRows(const DenoiseInputs& in, const float* source, float* out, int rowBegin,
                              int rowEnd) const {
  const size_t begin = 3 * size_t(rowBegin) * size_t(in.width), end = 3 * size_t(rowEnd) * size_t(in.width);
  for (size_t i = begin; i < end; ++i) out[i] = source[i] * demodulationDivisor(in.albedo[i]);
}

}  // namespace sdg
