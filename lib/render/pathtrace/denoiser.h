#pragma once
// The path tracer's denoiser: the edge-avoiding à-trous wavelet filter of
// Dammertz et al. 2010, "Edge-Avoiding À-Trous Wavelet Transform for fast
// Global Illumination Filtering", with SVGF's variance guidance (Schied et
// al. 2017) and weights made symmetric and doubly stochastic so that it
// moves light but neither loses nor gains any (Milanfar 2013, "Symmetrizing
// Smoothing Filters").
//
// Each iteration i convolves with the 5 x 5 B3-spline kernel whose taps are
// 2^i pixels apart, so three iterations reach 14 pixels away for the cost
// of 3 x 25 taps. A tap's weight w_pq is the kernel's times edge-stopping
// weights, each of them symmetric in p and q:
// - colour: exp(-|l_p - l_q| / (sigmaColor sigma_pq + 1 % of their mean
//   level)), l the luminance of the illumination and sigma_pq the mean of
//   the two pixels' noise (standard deviations): noise is smoothed, real
//   differences (shadow edges) are kept;
// - normal: max(0, n_p . n_q)^sigmaNormal (as SVGF);
// - depth: exp(-|z_p - z_q| / (sigmaDepth e + 1e-3 z)), e the mean of the
//   changes that planes through p and q with their own screen-space depth
//   gradients would make over the offset (SVGF's form, averaged), z their
//   mean depth: slanted planes smooth and steps do not;
// - instance: 0 between different ids, so edges between instances stay sharp.
//
// The normalisation: out_p = c_p + sum_q a_pq (c_q - c_p) with
// a_pq = w_pq / max(W_p, W_q), W the sum of a pixel's weights (the kernel's
// centre included). Symmetric, with rows summing to 1 and no negative
// entry: a doubly stochastic matrix, so each output is a convex combination
// and the sum over any region that edges close is kept exactly. The usual
// w_pq / W_p is not: a bright outlier that its neighbours' colour weights
// reject gives them little of its light, and path-tracing noise (rare,
// very bright paths) makes that loss systematic. On the Cornell box and the
// demo at 4 samples it darkened the image by 1.8 % and 4.6 % (block means
// of 16 frames, docs/performance.md); this form is off by 1.0 % and 1.1 %
// (the measurement's own noise: 0.5 % and 1.05 %), light moved across soft
// edges the guides do not see rather than lost, at a lower per-pixel error.
// It needs each pixel's W_p before filtering, so an iteration has three
// sweeps: the weights (each symmetric pair's once, kept: 12 a pixel), their
// sums W, the filter. On the CPU that takes 0.6 x the former filter's time
// (it computed all 24 weights per pixel); the GPU kernel recomputes them in
// two dispatches, 2.0 x its former time (0.36 ms at 512 x 512 on an H100).
//
// The noise: with a per-pixel variance from the tracer
// (DenoiseInputs::variance, the samples' own spread), SVGF's: the variance
// of the demodulated luminance, blurred 3 x 3 on the pixel's instance, then
// carried through every iteration with the squared coefficients of the
// taps (var' = sum a^2 var), so each iteration stops at differences of
// sigmaColor times the noise that is really left. Its first pass compares
// the pixels' 3 x 3 means rather than their own noisy values, so that a
// lone bright sample is not rejected by everything around it.
// Without one, the variance of the 5 x 5 neighbourhood, its scale shrunk
// by 2^-i/2 per iteration: that estimate also counts real edges and
// gradients as noise, so it lets the filter carry light across them.
//
// The filter runs on illumination, not radiance: radiance is divided by the
// albedo before filtering and multiplied by it after (where a channel of
// the albedo is below 1e-3, by 1 instead), so texture detail survives
// whatever the filter blurs. That is the albedo's role as a guide.
//
// Pixels without a surface (normal zero, depth not finite) keep their own
// radiance: no tap reaches them or leaves them.
//
// Deterministic: each output pixel is a fixed function of the inputs,
// whatever the thread count; rows are split among threads that meet at a
// barrier between sweeps. The scratch buffers belong to the Denoiser and
// are reused while the image size allows.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sdg {

// Per-pixel planes, rows top to bottom, each width * height pixels.
struct DenoiseInputs {
  int width = 0;
  int height = 0;
  const float* radiance = nullptr;     // RGB, linear, the noisy estimate
  const float* albedo = nullptr;       // RGB, the first surface's albedo
  const float* normal = nullptr;       // XYZ unit normals (any frame, one for the image); zero: no surface
  const float* depth = nullptr;        // distance along the view; not finite: no surface
  const uint32_t* instance = nullptr;  // optional: instance id per pixel
  // Optional: the variance of each pixel's mean luminance (its samples'
  // variance over their count); null: estimated from the neighbourhood.
  const float* variance = nullptr;
};

struct DenoiseSettings {
  int iterations = 3;  // 0 to 16; 3 (taps up to 8 pixels apart): 4 blur the Cornell box's light more at 4 samples
  // Colour edges stop the filter where two pixels' illumination differs by
  // more than about sigmaColor times their noise (see above).
  float sigmaColor = 4.0f;
  // ... and that scale times sigmaColorDecay^i in iteration i, whose taps
  // are 2^i pixels apart: the wider a pass reaches, the more of the
  // difference it meets is a real gradient (a lamp's falloff across a wall)
  // rather than noise the variance estimate missed. 0.8 took the area-lamp
  // room's one-frame block error at 4 samples from 1.48 to 1.41 % and its
  // bias (paired, 8 frames) from 0.87 to 0.70 %, at an MAE 3.8 -> 4.1 %
  // (the demo's stage 0.95 -> 0.90 %, MAE 3.8 -> 4.0 %); 2 passes instead
  // of 3 gave the same block error at an MAE of 4.8 % (docs/performance.md).
  float sigmaColorDecay = 0.8f;
  float sigmaNormal = 128.0f;
  // Depth steps stop it beyond sigmaDepth times the change the pixels'
  // depth gradients predict: 3 rather than 1, since along a floor seen at a
  // grazing angle depth grows faster than linearly across the screen (the
  // demo's floor: MAE 8.9 % -> 8.2 % at 4 samples, the Cornell box's bias
  // and MAE a little lower too).
  float sigmaDepth = 3.0f;
  // Threads filtering rows; 0: the hardware's count.
  unsigned threads = 0;
};

// Iteration i's colour scale (sigmaColor in the weights above): with a
// per-pixel variance sigmaColor, without one shrunk by 2^-i/2; both times
// sigmaColorDecay^i. The GPU denoiser gets it from here too.
float denoisePassSigmaColor(const DenoiseSettings& settings, int iteration, bool perPixelVariance);

class Denoiser {
 public:
  // Throws std::invalid_argument on iterations outside 0 to 16.
  explicit Denoiser(DenoiseSettings settings = {});

  // Writes width * height RGB pixels to `out`, which may be the radiance
  // plane itself.
  // Throws std::invalid_argument on a negative size or a missing plane.
  void run(const DenoiseInputs& inputs, float* out);

 private:
  void prepareRows(const DenoiseInputs& in, int rowBegin, int rowEnd);
  void estimateNoiseRows(const DenoiseInputs& in, int rowBegin, int rowEnd);
  // What one iteration's taps read.
  struct PassView {
    int step = 1;                    // 2^iteration pixels between taps
    const float* source = nullptr;   // the illumination being filtered, RGB
    const float* variance = nullptr; // its noise's variance per pixel
    const float* guide = nullptr;    // the luminance the colour weight compares; null: the source's
    float sigmaColor = 0.0f;
  };
  PassView passView(int iteration, const float* source, const float* varianceSource) const;
  float tapWeight(const DenoiseInputs& in, const PassView& pass, std::size_t p, std::size_t q, int kx,
                  int ky) const;
  void levelRows(const DenoiseInputs& in, const PassView& pass, int rowBegin, int rowEnd);
  void weighRows(const DenoiseInputs& in, const PassView& pass, int rowBegin, int rowEnd);
  void totalRows(const DenoiseInputs& in, const PassView& pass, int rowBegin, int rowEnd);
  void filterRows(const DenoiseInputs& in, const PassView& pass, float* target, float* varianceTarget, int rowBegin,
                  int rowEnd) const;
  void remodulateRows(const DenoiseInputs& in, const float* source, float* out, int rowBegin, int rowEnd) const;

  DenoiseSettings settings_;
  std::vector<float> illuminationA_, illuminationB_;  // RGB, ping-pong between iterations
  std::vector<float> depthGradient_;                  // d depth / dx, d depth / dy
  std::vector<float> noiseVariance_;                  // the input's local variance of luminance (spatial estimate)
  std::vector<float> levels_;                         // per pixel: luminance and noise of the iteration's input
  std::vector<float> halfWeights_;                    // per pixel, the weights of the 12 taps after it (weighRows)
  std::vector<float> weightTotal_;                    // each pixel's sum of tap weights in the current iteration
  std::vector<float> pixelVariance_;                  // the demodulated luminance's, from DenoiseInputs::variance
  std::vector<float> varianceA_, varianceB_;          // its estimate after each iteration, ping-pong
  std::vector<float> guide_;                          // the demodulated luminance blurred 3 x 3
};

}  // namespace sdg
