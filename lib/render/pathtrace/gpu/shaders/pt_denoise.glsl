#version 450
// The denoiser on the GPU: a port of denoiser.cpp (the edge-avoiding
// à-trous filter with symmetric weights normalised to a doubly stochastic
// matrix, demodulated by the albedo, per-pixel or spatial noise estimate),
// run on the tracer's film before it is read back. One pass per dispatch:
// 0 prepares (illumination, depth gradient), 1 estimates the noise; per
// iteration 4 sums each pixel's tap weights and 2 filters once (from region
// `source` to the other); 3 remodulates into the film's sum (which then
// holds the radiance itself, not a sum of samples), so the work planes
// never leave the device. Each invocation writes its own pixel only.
layout(local_size_x = 8, local_size_y = 8) in;

struct FilmPixel {
  vec4 sum;
  vec4 albedo;
  vec4 normalDepth;
  uvec4 rays;  // w: the instance id
};
layout(std430, binding = 1) buffer Film { FilmPixel film[]; };
// Five regions of width * height: illumination A and B (w: the variance
// carried with them, in the per-pixel variance mode), (depth gradient x, y,
// the spatial noise variance or the pixel's own variance, instance id), the
// guides (normal, depth), (the 3 x 3 luminance guide of the first pass, the
// current iteration's weight sums W). Pass 0 copies the guides out of the
// film, so the taps of the later passes read this buffer alone.
layout(std430, binding = 2) buffer Work { vec4 work[]; };

uniform int width, height, samples, pass_, iteration, source, useVariance;
uniform float sigmaColor, sigmaNormal, sigmaDepth;

const float kKernel[5] = float[5](1.0 / 16.0, 1.0 / 4.0, 3.0 / 8.0, 1.0 / 4.0, 1.0 / 16.0);
const float kMinAlbedo = 1e-3;
const float kRelativeDepthTolerance = 1e-3;
const float kInfinity = uintBitsToFloat(0x7f800000u);
const float kFloatMin = 1.17549435e-38;

bool finite(float v) { return !isinf(v) && !isnan(v); }
float luminance(vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }
vec3 divisor(vec3 albedo) {
  return vec3(albedo.x >= kMinAlbedo ? albedo.x : 1.0, albedo.y >= kMinAlbedo ? albedo.y : 1.0,
              albedo.z >= kMinAlbedo ? albedo.z : 1.0);
}
bool hasSurface(vec4 normalDepth) { return finite(normalDepth.w) && normalDepth.xyz != vec3(0.0); }
float gentlerDifference(float backward, float forward) {
  float mb = finite(backward) ? abs(backward) : kInfinity, mf = finite(forward) ? abs(forward) : kInfinity;
  float chosen = mb <= mf ? backward : forward;
  return finite(chosen) ? chosen : 0.0;
}

// What a tap's weight reads of one pixel: (depth gradient, id), (normal,
// depth), the luminance the colour weight compares and the noise's
// standard deviation (denoiser.cpp's levels).
struct TapPixel {
  vec4 aux;
  vec4 guide;
  float level;
  float noise;
};
float noiseVariance(uint q, uint from) {
  uint n = uint(width) * uint(height);
  return useVariance != 0 ? work[from + q].w : work[2u * n + q].z;
}
TapPixel tapPixel(uint q, uint from) {
  uint n = uint(width) * uint(height);
  TapPixel t;
  t.aux = work[2u * n + q];
  t.guide = work[3u * n + q];
  t.level = useVariance != 0 && iteration == 0 ? work[4u * n + q].x : luminance(work[from + q].xyz);
  t.noise = sqrt(noiseVariance(q, from));
  return t;
}
// denoiser.cpp's tapWeight: the symmetric edge-stopping weight of the tap
// from p to q (p != q, q - p = (kx, ky) taps), the kernel's weight included.
float tapWeight(TapPixel p, TapPixel q, int kx, int ky, int step) {
  if (q.aux.w != p.aux.w) return 0.0;
  float cosine = dot(p.guide.xyz, q.guide.xyz);
  float dz = abs(q.guide.w - p.guide.w);
  if (!(cosine > 0.0) || !finite(dz)) return 0.0;
  float dx = float(kx * step), dy = float(ky * step);
  float expectedDz = abs(p.aux.x * dx + p.aux.y * dy) + abs(q.aux.x * dx + q.aux.y * dy);
  float depthScale =
      0.5 * sigmaDepth * expectedDz + 0.5 * kRelativeDepthTolerance * (abs(p.guide.w) + abs(q.guide.w));
  // sigmaColor: this iteration's scale (denoiser.h's denoisePassSigmaColor, set per iteration).
  float colorScale = 0.5 * sigmaColor * (p.noise + q.noise) + 0.005 * (abs(p.level) + abs(q.level)) + 1e-6;
  return kKernel[kx + 2] * kKernel[ky + 2] *
         exp(sigmaNormal * log(cosine) - dz / max(depthScale, kFloatMin) - abs(q.level - p.level) / colorScale);
}

void main() {
  int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= width || y >= height) return;
  uint n = uint(width) * uint(height);
  uint p = uint(y) * uint(width) + uint(x);
  if (pass_ == 0) {
    vec3 radiance = film[p].sum.xyz / float(samples);
    work[p] = vec4(radiance / divisor(film[p].albedo.xyz), 0.0);
    float z = film[p].normalDepth.w;
    float gx = gentlerDifference(x > 0 ? z - film[p - 1u].normalDepth.w : kInfinity,
                                 x + 1 < width ? film[p + 1u].normalDepth.w - z : kInfinity);
    float gy = gentlerDifference(y > 0 ? z - film[p - uint(width)].normalDepth.w : kInfinity,
                                 y + 1 < height ? film[p + uint(width)].normalDepth.w - z : kInfinity);
    float pixelVariance = 0.0;
    if (useVariance != 0) {
      // The samples' variance of the mean luminance (path_tracer.cpp's), then demodulated (denoiser.cpp's prepareRows).
      float count = float(samples);
      float mean = luminance(film[p].sum.xyz) / count;
      float variance = samples > 1 ? max(0.0, film[p].albedo.w / count - mean * mean) / (count - 1.0) : 0.0;
      float radianceL = luminance(radiance), illuminationL = luminance(work[p].xyz);
      float scale = radianceL > 0.0 ? illuminationL / radianceL : 1.0 / luminance(divisor(film[p].albedo.xyz));
      pixelVariance = variance * scale * scale;
    }
    work[2u * n + p] = vec4(gx, gy, pixelVariance, float(film[p].rays.w));  // ids are exact as floats below 2^24
    work[3u * n + p] = film[p].normalDepth;
  } else if (pass_ == 1 && useVariance != 0) {
    // SVGF: the per-pixel variance and the luminance blurred 3 x 3 on the pixel's instance.
    const float kGauss[3] = float[3](0.25, 0.5, 0.25);
    float sum = 0.0, guide = 0.0, weights = 0.0;
    float id = work[2u * n + p].w;
    for (int qy = max(0, y - 1); qy <= min(height - 1, y + 1); ++qy)
      for (int qx = max(0, x - 1); qx <= min(width - 1, x + 1); ++qx) {
        uint q = uint(qy) * uint(width) + uint(qx);
        if (q != p && (!hasSurface(work[3u * n + q]) || work[2u * n + q].w != id)) continue;
        float weight = kGauss[qx - x + 1] * kGauss[qy - y + 1];
        sum += weight * work[2u * n + q].z;
        guide += weight * luminance(work[q].xyz);
        weights += weight;
      }
    work[p].w = sum / weights;
    work[4u * n + p] = vec4(guide / weights, 0.0, 0.0, 0.0);
  } else if (pass_ == 1) {
    float sum = 0.0, sum2 = 0.0;
    int count = 0;
    float id = work[2u * n + p].w;
    for (int qy = max(0, y - 2); qy <= min(height - 1, y + 2); ++qy)
      for (int qx = max(0, x - 2); qx <= min(width - 1, x + 2); ++qx) {
        uint q = uint(qy) * uint(width) + uint(qx);
        if (!hasSurface(work[3u * n + q]) || work[2u * n + q].w != id) continue;
        float l = luminance(work[q].xyz);
        sum += l;
        sum2 += l * l;
        ++count;
      }
    float c = float(count);
    work[2u * n + p].z = count > 1 ? max(0.0, sum2 / c - (sum / c) * (sum / c)) : 0.0;
  } else if (pass_ == 2 || pass_ == 4) {
    // 4: W_p, the sum of p's tap weights (into region 4, y; denoiser.cpp's
    // totalRows); 2: one filter iteration, a_pq = w_pq / max(W_p, W_q),
    // doubly stochastic (filterRows). denoiser.cpp computes each pair's
    // weight once and keeps it; here each dispatch computes its own, in
    // reading order: on an H100 at 512 x 512 that took 0.36 ms, against
    // 0.50 ms with the weights kept (a third dispatch, 12 more floats a
    // pixel) and 0.59 ms in denoiser.cpp's tap order.
    uint from = uint(source) * n, to = uint(1 - source) * n;
    vec4 sp = work[from + p];
    if (!hasSurface(work[3u * n + p])) {
      if (pass_ == 2) work[to + p] = sp;
      return;
    }
    float totalP = pass_ == 2 ? work[4u * n + p].y : 0.0;
    TapPixel own = tapPixel(p, from);
    float weightSum = 0.0, varianceSum = 0.0;
    vec3 sum = vec3(0.0);
    int step = 1 << iteration;
    for (int ky = -2; ky <= 2; ++ky) {
      int qy = y + ky * step;
      if (qy < 0 || qy >= height) continue;
      for (int kx = -2; kx <= 2; ++kx) {
        int qx = x + kx * step;
        if (qx < 0 || qx >= width || (kx == 0 && ky == 0)) continue;
        uint q = uint(qy) * uint(width) + uint(qx);
        float weight = tapWeight(own, tapPixel(q, from), kx, ky, step);
        if (weight == 0.0) continue;
        if (pass_ == 4) {
          weightSum += weight;
          continue;
        }
        float a = weight / max(totalP, work[4u * n + q].y);
        vec4 sq = work[from + q];
        sum += a * sq.xyz;
        weightSum += a;
        varianceSum += a * a * noiseVariance(q, from);
      }
    }
    if (pass_ == 4) {
      work[4u * n + p].y = kKernel[2] * kKernel[2] + weightSum;
      return;
    }
    float kept = 1.0 - weightSum;
    work[to + p] = vec4(sum + kept * sp.xyz, useVariance != 0 ? varianceSum + kept * kept * sp.w : 0.0);
  } else {
    film[p].sum.xyz = work[uint(source) * n + p].xyz * divisor(film[p].albedo.xyz);
  }
}
