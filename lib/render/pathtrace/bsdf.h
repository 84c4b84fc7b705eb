#pragma once
// The path tracer's surface model: OmniPBR's metallic-roughness material as
// a reflection-only BSDF in a local shading frame (normal = +Z).
//
// Lobes:
// - specular: GGX microfacets (Walter et al. 2007) with Smith's
//   height-correlated masking-shadowing (Heitz 2014) and Schlick's Fresnel,
//   F0 = mix(0.04, baseColor, metallic); sampled by the distribution of
//   visible normals (Heitz 2018, "Sampling the GGX Distribution of Visible
//   Normals");
// - diffuse: Lambert, (1 - metallic) baseColor / pi, not darkened by the
//   coat, as in the rasterizer's shading and Blender's Principled BSDF, so
//   the modes and the Cycles comparison (tools/cycles) agree on a material;
//   a white dielectric therefore reflects a little more than it receives
//   (its coat's few per cent).
// - OmniPBR's specular_level scales the dielectric coat: F0 = 0.08 level
//   and F90 = 2 level (0.04 and 1 at the default 0.5); at 0 a dielectric is
//   pure Lambert, which the white furnace test uses.
//
// Single scattering: GGX loses the light that would bounce between
// microfacets, more the rougher the surface. A white metal keeps >= 99 % up
// to roughness 0.1, >= 84 % at 0.5, but only about 31 % at roughness 1 seen
// head-on (alpha = 1: half the reflections leave below the horizon). A white
// dielectric's coat adds its Fresnel reflectance (about 4 % head-on) to
// the diffuse base's full albedo.
//
// roughness is the perceptual one (OmniPBR's reflection_roughness): the
// GGX alpha is roughness^2, clamped to >= 1e-3 so a roughness of 0 is a very
// sharp but finite lobe: eval, pdf and weights stay finite, and every
// sample can take part in multiple importance sampling.
//
// Directions are unit vectors pointing away from the surface; wo toward the
// viewer, wi toward the light. Nothing is transmitted: wo or wi below the
// surface (cos <= 1e-6) gets zero.
#include <optional>

#include "stage/math_types.h"

namespace sdg {

struct PbrMaterial {
  Vec3f baseColor{0.2f, 0.2f, 0.2f};  // OmniPBR's defaults
  float metallic = 0.0f;
  float roughness = 0.5f;
  float specularLevel = 0.5f;  // OmniPBR's specular_level
};

struct BsdfSample {
  Vec3f wi;
  Vec3f weight;       // eval(wo, wi) / pdf(wo, wi): f cos θi over the density
  float pdf;          // pdf(wo, wi): the density of sample() over both lobes
  bool specular;      // drawn from the GGX lobe (never a delta: pdf is finite)
};

// f cos θi of each lobe apart: a light's inputs:diffuse and inputs:specular
// scale them apart (pt_lights.h).
struct BsdfLobes {
  Vec3f diffuse;
  Vec3f specular;
};

class PbrBsdf {
 public:
  explicit PbrBsdf(const PbrMaterial& material);

  // f(wo, wi) cos θi.
  Vec3f eval(const Vec3f& wo, const Vec3f& wi) const;
  // The same, by lobe (eval() is their sum).
  BsdfLobes evalLobes(const Vec3f& wo, const Vec3f& wi) const;
  // The solid-angle density with which sample() returns wi: one-sample MIS
  // of the two lobes, each picked with the probability specularProbability().
  float pdf(const Vec3f& wo, const Vec3f& wi) const;
  // uLobe picks the lobe, u draws the direction in it. Empty when wo is
  // below the surface or the reflected direction falls below it.
  std::optional<BsdfSample> sample(const Vec3f& wo, const Vec2f& u, float uLobe) const;

  // The chance of sampling the GGX lobe: its Fresnel reflectance at wo
  // against the diffuse lobe's albedo estimate, by luminance.
  float specularProbability(const Vec3f& wo) const;

  // The path tracer asks one vertex's BSDF for several wi seen from the
  // same wo: a View holds what depends on wo alone, worked out once, and
  // these give exactly the numbers of the calls above.
  struct View {
    Vec3f wo;
    bool above = false;  // wo above the surface: anything reflected at all
    float lambdaWo = 0;  // Smith's Lambda at wo
    float specularProbability = 0;
  };
  View view(const Vec3f& wo) const;
  // evalLobes(wo, wi), and pdf(wo, wi) into `pdf`.
  BsdfLobes evalLobes(const View& view, const Vec3f& wi, float& pdf) const;
  // sample(wo, u, uLobe), and the sample's evalLobes into `lobes`.
  std::optional<BsdfSample> sample(const View& view, const Vec2f& u, float uLobe, BsdfLobes& lobes) const;

 private:
  Vec3f diffuseColor_;  // (1 - metallic) baseColor
  Vec3f f0_;
  float f90_ = 1.0f;  // the Fresnel term's grazing value
  float alpha_;
};

// An orthonormal basis around a unit normal n (Duff et al. 2017, "Building
// an Orthonormal Basis, Revisited"): right-handed, s x t = n, continuous
// except across n.z = 0's sign flip, exact at n = -Z.
struct ShadingFrame {
  Vec3f s, t, n;

  static ShadingFrame fromNormal(const Vec3f& n);
  Vec3f toLocal(const Vec3f& v) const { return {v.dot(s), v.dot(t), v.dot(n)}; }
  Vec3f toWorld(const Vec3f& v) const { return s * v.x() + t * v.y() + n * v.z(); }
};

}  // namespace sdg
