#pragma once
// Pre-filtering of a lat-long HDR dome for image-based lighting with the
// split-sum approximation (Karis 2013, "Real Shading in Unreal Engine 4"),
// on the CPU: a diffuse irradiance map, a specular mip chain whose levels
// are pre-convolved with the GGX lobe of growing roughness, and the BRDF
// table that scales and biases F0. All images follow latlong.h's mapping.
//
// The shader then lights a surface of albedo rho, roughness r and specular
// colour F0, seen along V, with normal n and mirror direction R = reflect(-V, n):
//   diffuse  = rho * irradiance(n)
//   specular = specular(R, lod = r * (specular.size() - 1)) * (F0 * scale + bias),
//              (scale, bias) = lut(N.V, r).
#include <vector>

#include "assets/image.h"
#include "stage/math_types.h"

namespace sdg {

// A lat-long image of linear RGB: 3 floats per texel, rows top to bottom
// (latlong.h's v = 0 first), ready for glTexImage2D(GL_RGB, GL_FLOAT).
struct LatLong {
  int width = 0;
  int height = 0;
  std::vector<float> rgb;
};

struct EnvironmentSettings {
  int irradianceWidth = 64;     // the irradiance map is this wide and half as tall (even, >= 2)
  int specularBaseWidth = 512;  // specular level 0 is at most this wide (and half as tall)
  int specularLevels = 6;       // fewer where level 0 reaches 1 x 1 first
  int specularSamples = 64;     // GGX samples per texel of level 1, doubling each level after (<= 4096)
  int threads = 0;              // 0: the hardware's, at most 8; the result does not depend on it
};

struct PrefilteredEnvironment {
  // E(n) / pi for the normal n at each texel's centre: the cosine-weighted
  // integral of the dome's radiance over the hemisphere around n, over pi,
  // so that a Lambertian surface of albedo rho reflects rho times it. A
  // brute-force convolution over a copy of the dome twice this map's size,
  // with each texel's cosine integrated exactly (not taken at its centre).
  LatLong irradiance;
  // The levels of one GL texture (each half the previous, GL's floor rule;
  // usually not down to 1 x 1, so GL_TEXTURE_MAX_LEVEL = size() - 1).
  // Level 0 is the dome area-downsampled (weighted by solid angle, so its
  // integral over the sphere is kept); level k is that image convolved with
  // the GGX lobe of perceptual roughness k / (levels - 1) (alpha = r^2),
  // under Karis's N = V = R assumption and weighted by N.L, by filtered
  // importance sampling (Colbert and Krivanek, GPU Gems 3, ch. 20).
  std::vector<LatLong> specular;
};

// Throws std::invalid_argument for an empty map or settings out of range.
PrefilteredEnvironment prefilterEnvironment(const ImageRgbaF& map, const EnvironmentSettings& settings = {});

// Karis's table of the specular BRDF's directional albedo, split as
// F0 * scale + bias, for GGX with the Smith-Schlick visibility k = alpha / 2
// and Schlick Fresnel: the same terms as brdf() in shaders.h (alpha clamped
// to at least 1e-3 as there).
struct SplitSumLut {
  int size = 0;
  // (scale, bias) at texel (i, j), index 2 * (j * size + i): N.V = (i + 0.5)
  // / size, roughness = (j + 0.5) / size. The first row is GL's t = 0 side,
  // so the shader samples it at (N.V, roughness) with CLAMP_TO_EDGE.
  std::vector<float> scaleBias;
};

// 1024 GGX samples per texel, as Karis; throws std::invalid_argument for
// a size under 1.
SplitSumLut integrateSplitSumLut(int size = 32);

// The solid angle of a texel of row `row` of a width x height lat-long map.
double latLongTexelSolidAngle(int width, int height, int row);

// The image's radiance along the unit direction `dir`, bilinear, wrapping in
// u and clamped in v: what GL's sampler returns with GL_REPEAT on s and
// GL_CLAMP_TO_EDGE on t.
Vec3f sampleBilinear(const LatLong& image, const Vec3f& dir);

}  // namespace sdg
