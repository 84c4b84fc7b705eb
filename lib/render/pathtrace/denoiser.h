#pragma once
// The path tracer's denoiser: the edge-avoiding à-trous wavelet filter of
// Dammertz et al. 2010, "Edge-Avoiding À-Trous Wavelet Transform for fast
// Global Illumination Filtering".
//
// Each iteration i convolves with the 5 x 5 B3-spline kernel whose taps are
// 2^i pixels apart, so five iterations reach 125 pixels for the cost of
// 5 x 25 taps. A tap's weight is the kernel's times edge-stopping weights:
// - colour: exp(-d^2 / sigmaColor_i^2), with d the L1 distance of the two
//   pixels' colours over their mean L1 magnitude (so it does not depend on
//   exposure) and sigmaColor_i = sigmaColor 2^-i, as in the paper: each
//   iteration sees less noise, so it may stop at smaller differences;
// - normal: max(0, n_p . n_q)^sigmaNormal (as SVGF, Schied et al. 2017);
// - depth: exp(-|z_p - z_q| / (sigmaDepth |grad z_p . (q - p)| + 1e-3 z_p)),
//   the change a plane through p with p's screen-space depth gradient
//   would make (SVGF's form), so slanted planes smooth and steps do not;
// - instance: 0 between different ids, so edges between instances stay sharp.
//
// The colour scale: with a per-pixel variance from the tracer
// (DenoiseInputs::variance, the samples' own spread), SVGF's (Schied et
// al. 2017): the variance of the demodulated luminance, blurred 3 x 3 on the
// pixel's instance, then carried through every iteration with the squared
// weights of the taps (var' = sum w^2 var / (sum w)^2), so each iteration
// stops at differences of sigmaColor times the noise that is really left.
// Its first pass compares the pixels' 3 x 3 means rather than their own
// noisy values: weights that favour values near a noisy centre pull the
// skewed noise of a few samples (rare bright paths) toward its mode and
// darken the image (the bias a block mean shows).
// Without one, the standard deviation of the 5 x 5 neighbourhood, scaled
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
// barrier between iterations. The scratch buffers belong to the Denoiser
// and are reused while the image size allows.
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
  int iterations = 3;  // 0 to 16; 3 (taps up to 8 pixels apart) measured least biased at 4 samples
  // Colour edges stop the filter where two pixels' illumination differs by
  // more than sigmaColor times the pixel's noise (the standard deviation of
  // its 5 x 5 neighbourhood, as SVGF's spatial estimate): noise is smoothed,
  // real differences (shadow edges) are kept.
  float sigmaColor = 4.0f;
  float sigmaNormal = 128.0f;
  float sigmaDepth = 1.0f;
  // Threads filtering rows; 0: the hardware's count.
  unsigned threads = 0;
};

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
  void filterRows(const DenoiseInputs& in, int iteration, const float* source, float* target,
                  const float* varianceSource, float* varianceTarget, int rowBegin, int rowEnd) const;
  void remodulateRows(const DenoiseInputs& in, const float* source, float* out, int rowBegin, int rowEnd) const;

  DenoiseSettings settings_;
  std::vector<float> illuminationA_, illuminationB_;  // RGB, ping-pong between iterations
  std::vector<float> depthGradient_;                  // d depth / dx, d depth / dy
  std::vector<float> noise_;                          // the input's local standard deviation of luminance
  std::vector<float> pixelVariance_;                  // the demodulated luminance's, from DenoiseInputs::variance
  std::vector<float> varianceA_, varianceB_;          // its estimate after each iteration, ping-pong
  std::vector<float> guide_;                          // the demodulated luminance blurred 3 x 3
};

}  // namespace sdg
