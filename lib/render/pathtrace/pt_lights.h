#pragma once
// The path tracer's lights: every USD light the rasterizer supports, with
// its radiometry (render_list.cpp: radiance = intensity x 2^exposure x
// colour; render/shaders.h), sampled for next-event estimation and
// intersected analytically by the rays that reach them (lights are not in
// the Embree scene), each with the density multiple importance sampling
// needs (Veach 1997, ch. 9; pbrt-v4 13.4).
//
// - SphereLight: a sphere of that radiance; sampled uniformly over the cone
//   it subtends (pbrt-v4 6.2.4). Head-on irradiance pi L sin^2(alpha) =
//   L pi r^2 / d^2: the rasterizer's L x area / d^2.
// - RectLight (width along local X, height along Y) and DiskLight (radius):
//   one-sided, emitting toward the light's -Z (RenderLight::direction);
//   sampled uniformly by area.
// - CylinderLight: the lateral surface (length along local X, radius),
//   emitting outward, the caps dark; sampled uniformly by area (the far
//   half faces away and gives nothing).
// - DistantLight: RenderLight::radiance is the irradiance at normal
//   incidence, as in the rasterizer. Angle 0 is a delta light; otherwise a
//   cone of that angular diameter and radiance E / (pi sin^2(angle / 2)),
//   which gives E at normal incidence; sampled uniformly over the cone.
// - DomeLight: the first dome with a texture shows its lat-long map
//   (render/latlong.h, in the frame RenderLight::worldRotation) times its
//   radiance; the others add their uniform radiance (the rasterizer lets a
//   textured dome replace them instead). Sampled by the map
//   (EnvironmentSampler, whose texels the radiance is read from) mixed, by
//   power, with a cosine lobe around the shading normal for the uniform part.
//
// - A SphereLight with treatAsPoint is a point of the same power (radiant
//   intensity L pi r^2, the rasterizer's): a delta light, hard shadows, no
//   shape for rays to hit.
//
// A light's inputs:diffuse and inputs:specular scale what it sends through
// the BSDF's diffuse and specular lobes apart (response()), at every
// vertex: next-event estimation and BSDF samples that find it alike.
// inputs:normalize is in the radiance already (render_list.cpp).
//
// Sizes are the lights' own attributes, positions and frames their world
// transforms without scale, as in the rasterizer.
//
// Every ray sees the lights, camera rays included: a light shape shows its
// radiance, a distant light with an angle its disk (the sun in the sky),
// where the rasterizer shows neither.
//
// Light shapes are seen only from their emitting side: they stop the rays
// that hit that side (which count the emission) and let every other ray
// pass, shadow rays included, so both strategies of MIS see the same
// lights. One light is picked per shading point, by an estimate of its power.
#include <cstdint>
#include <functional>
#include <vector>

#include "render/pathtrace/bsdf.h"
#include "render/pathtrace/embree_scene.h"
#include "render/pathtrace/environment_sampler.h"
#include "render/render_list.h"

namespace sdg {

// A dome's map, loaded once: linear RGBA and its importance sampler.
struct PtDomeMap {
  ImageRgbaF image;
  EnvironmentSampler sampler;
  Vec3f mean;  // the map's radiance averaged over the sphere (solid-angle weighted)

  explicit PtDomeMap(ImageRgbaF map);
  Vec3f radiance(const Vec3f& domeDirection) const;  // the texel holding the direction, as sampled
};

struct LightSample {
  Vec3f direction;  // unit, toward the light
  float distance;   // to the point sampled; +inf for distant and dome lights
  Vec3f radiance;   // arriving along `direction` (irradiance for a delta light)
  float pdf;        // solid-angle density, times the light's pick probability
  bool delta;
  int light;
};

struct LightHit {
  int light = -1;
  float t = 0;
  Vec3f radiance = Vec3f::Zero();
};

class PtLights {
 public:
  // One light as sample() reads it; public for the GPU tracer, which uploads it (render/pathtrace/gpu).
  struct Light {
    LightKind kind = LightKind::Sphere;
    Vec3f radiance = Vec3f::Zero();  // emitted; a delta distant light's irradiance
    Vec3f position = Vec3f::Zero();
    Vec3f axisX = Vec3f::UnitX(), axisY = Vec3f::UnitY(), axisZ = Vec3f::UnitZ();  // the light's frame
    Vec3f emit = -Vec3f::UnitZ();  // it emits along its -Z
    float radius = 0, width = 0, height = 0, length = 0, area = 0;
    // Distant: toward the light, the cone's 1 - cos and sin^2 of its half-angle.
    Vec3f toLight = Vec3f::UnitZ();
    float oneMinusCos = 0, sin2Half = 0;
    bool delta = false;
    bool point = false;  // a sphere light with treatAsPoint
    float diffuse = 1, specular = 1;  // inputs:diffuse, inputs:specular
    // Dome: the textured map (may be null), its scale and frame, the uniform part.
    const PtDomeMap* map = nullptr;
    Eigen::Matrix3f domeFromWorld = Eigen::Matrix3f::Identity();
    Vec3f mapScale = Vec3f::Zero();
    Vec3f ambient = Vec3f::Zero();
    float mapProbability = 0;  // of sampling by the map rather than the cosine lobe
    float pick = 0;            // the probability of picking this light
  };

  PtLights();
  ~PtLights();
  // `domeMap` loads (or finds) a dome's map by its light.
  void build(const RenderList& list, const Eigen::AlignedBox3f& sceneBounds,
             const std::function<const PtDomeMap*(const RenderLight&)>& domeMap);

  bool empty() const { return lights_.empty(); }
  // Picks a light with uPick and samples a direction toward it with u, seen
  // from p with shading normal n. False when the pick gives nothing.
  bool sample(const Vec3f& p, const Vec3f& n, float uPick, const Vec2f& u, LightSample& out) const;
  // The closest emitting face of a light shape along the ray, in (tMin, tMax).
  bool intersect(const PtRay& ray, LightHit& hit) const;
  // Whether a light shape other than `except` stops the ray in (tMin, tMax).
  bool blocks(const PtRay& ray, int except) const;
  // sample()'s density (pick included) for the direction `wi` from (p, n)
  // that reaches light `light` (a shape, hit first along wi).
  float pdf(int light, const Vec3f& p, const Vec3f& n, const Vec3f& wi) const;
  // What the distant lights and the dome send along a ray that left the
  // scene from p (shading normal n) in direction wi. With bsdfPdf > 0 each
  // light's share is weighted by the power heuristic against its light
  // sampling density; with bsdfPdf <= 0 (camera rays) it is unweighted.
  // `lobes`: the BSDF's lobes along wi at p, for the lights' diffuse and
  // specular multipliers (null: camera rays, no surface).
  Vec3f escaped(const Vec3f& p, const Vec3f& n, const Vec3f& wi, float bsdfPdf, const BsdfLobes* lobes = nullptr) const;

  // f cos as light `light` sees it: diffuse x f_d + specular x f_s (the
  // plain sum where both multipliers are 1).
  Vec3f response(int light, const BsdfLobes& f) const;
  // response() over f_d + f_s: the factor on light that a BSDF sample finds.
  Vec3f responseScale(int light, const BsdfLobes& f) const;
  // Whether any light has a diffuse or specular multiplier other than 1.
  bool anyLobeMultiplier() const { return anyLobeMultiplier_; }

  const std::vector<Light>& lights() const { return lights_; }
  const std::vector<float>& pickCdf() const { return pickCdf_; }

 private:
  bool hitShape(const Light& light, const PtRay& ray, float& t) const;
  float densityOf(const Light& light, const Vec3f& p, const Vec3f& n, const Vec3f& wi) const;
  Vec3f domeRadiance(const Light& light, const Vec3f& wi) const;

  std::vector<Light> lights_;
  std::vector<float> pickCdf_;  // lights_.size() + 1 entries, 0 .. 1
  bool anyLobeMultiplier_ = false;
};

// The power heuristic with exponent 2 (Veach 1997, 9.2.4) for a strategy
// of density a against one of density b.
inline float powerHeuristic(float a, float b) {
  const float a2 = a * a, b2 = b * b;
  if (!(a2 > 0.0f)) return 0.0f;
  if (a2 > 1e30f) return 1.0f;  // an infinite or enormous density takes everything
  return a2 / (a2 + b2);
}

}  // namespace sdg
