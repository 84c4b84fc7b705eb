#include "render/pathtrace/bsdf.h"

#include <algorithm>
#include <cmath>

namespace sdg {
namespace {

constexpr float kPi = 3.14159265358979323846f;
// Below this cosine a direction counts as on or under the surface: it keeps
// tan^2 θ <= 1e12, so the Smith terms stay finite.
constexpr float kMinCos = 1e-6f;
constexpr float kMinAlpha = 1e-3f;
constexpr float kDielectricF0 = 0.04f;

float luminance(const Vec3f& c) { return 0.2126f * c.x() + 0.7152f * c.y() + 0.0722f * c.z(); }

// Schlick's (1 - cos)^5.
float schlickWeight(float cosTheta) {
  const float m = std::clamp(1.0f - cosTheta, 0.0f, 1.0f);
  const float m2 = m * m;
  return m2 * m2 * m;
}

Vec3f schlickFresnel(const Vec3f& f0, float f90, float cosTheta) {
  return f0 + (Vec3f::Constant(f90) - f0) * schlickWeight(cosTheta);
}

// GGX's normal distribution, D = alpha^2 / (pi (cos^2 (alpha^2 - 1) + 1)^2),
// rewritten as 1 / (pi alpha^2 (sin^2 / alpha^2 + cos^2)^2) so it stays
// accurate when alpha^2 is far below float's epsilon against 1.
float ggxDistribution(const Vec3f& h, float alpha) {
  const float a2 = alpha * alpha;
  const float d = (h.x() * h.x() + h.y() * h.y()) / a2 + h.z() * h.z();
  return 1.0f / (kPi * a2 * d * d);
}

// Smith's Lambda for GGX: (sqrt(1 + alpha^2 tan^2 θ) - 1) / 2.
float smithLambda(const Vec3f& w, float alpha) {
  const float tan2 = (w.x() * w.x() + w.y() * w.y()) / (w.z() * w.z());
  return 0.5f * (std::sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
}

// A microfacet normal drawn from the normals visible from wo, with density
// G1(wo) max(0, wo.h) D(h) / cos θo (Heitz 2018): stretch the view so the
// GGX ellipsoid becomes a hemisphere, draw a point of its projected area (a
// half disk and a half ellipse), lift it onto the hemisphere, unstretch.
Vec3f sampleVisibleNormal(const Vec3f& wo, float alpha, const Vec2f& u) {
  const Vec3f v = Vec3f(alpha * wo.x(), alpha * wo.y(), wo.z()).normalized();
  const float horizontal2 = v.x() * v.x() + v.y() * v.y();
  const Vec3f t1 = horizontal2 > 0.0f ? Vec3f(-v.y(), v.x(), 0.0f) / std::sqrt(horizontal2) : Vec3f(1.0f, 0.0f, 0.0f);
  const Vec3f t2 = v.cross(t1);
  const float r = std::sqrt(u.x());
  const float phi = 2.0f * kPi * u.y();
  const float p1 = r * std::cos(phi);
  const float blend = 0.5f * (1.0f + v.z());
  const float p2 = (1.0f - blend) * std::sqrt(std::max(0.0f, 1.0f - p1 * p1)) + blend * r * std::sin(phi);
  const Vec3f onHemisphere = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0f, 1.0f - p1 * p1 - p2 * p2)) * v;
  return Vec3f(alpha * onHemisphere.x(), alpha * onHemisphere.y(), std::max(0.0f, onHemisphere.z())).normalized();
}

// Cosine-weighted hemisphere through Shirley and Chiu's concentric map of
// the square onto the disk, which keeps the sampler's stratification.
Vec3f sampleCosineHemisphere(const Vec2f& u) {
  const float a = 2.0f * u.x() - 1.0f;
  const float b = 2.0f * u.y() - 1.0f;
  if (a == 0.0f && b == 0.0f) return {0.0f, 0.0f, 1.0f};
  float radius, phi;
  if (std::abs(a) > std::abs(b)) {
    radius = a;
    phi = 0.25f * kPi * (b / a);
  } else {
    radius = b;
    phi = 0.5f * kPi - 0.25f * kPi * (a / b);
  }
  const float x = radius * std::cos(phi);
  const float y = radius * std::sin(phi);
  return {x, y, std::sqrt(std::max(0.0f, 1.0f - x * x - y * y))};
}

}  // namespace

PbrBsdf::PbrBsdf(const PbrMaterial& material) {
  const float metallic = std::clamp(material.metallic, 0.0f, 1.0f);
  const float roughness = std::clamp(material.roughness, 0.0f, 1.0f);
  const float coat = 2.0f * std::clamp(material.specularLevel, 0.0f, 1.0f);  // 1 at OmniPBR's default
  diffuseColor_ = (1.0f - metallic) * material.baseColor;
  f0_ = Vec3f::Constant(kDielectricF0 * coat * (1.0f - metallic)) + metallic * material.baseColor;
  f90_ = coat * (1.0f - metallic) + metallic;
  alpha_ = std::max(roughness * roughness, kMinAlpha);
}

PbrBsdf::View PbrBsdf::view(const Vec3f& wo) const {
  View v;
  v.wo = wo;
  v.above = wo.z() > kMinCos;
  if (v.above) v.lambdaWo = smithLambda(wo, alpha_);
  v.specularProbability = specularProbability(wo);
  return v;
}

BsdfLobes PbrBsdf::evalLobes(const View& view, const Vec3f& wi, float& pdf) const {
  pdf = 0.0f;
  if (!view.above || wi.z() <= kMinCos) return {Vec3f::Zero(), Vec3f::Zero()};
  const Vec3f& wo = view.wo;
  const Vec3f diffuse = diffuseColor_ * (wi.z() / kPi);
  // f = F D G2 / (4 cos θo cos θi); times cos θi.
  const Vec3f h = (wo + wi).normalized();
  const float d = ggxDistribution(h, alpha_);
  const float g2 = 1.0f / (1.0f + view.lambdaWo + smithLambda(wi, alpha_));
  const Vec3f specular = schlickFresnel(f0_, f90_, wo.dot(h)) * (d * g2 / (4.0f * wo.z()));
  // The density: visible normals, D_wo(h) = G1(wo) (wo.h) D(h) / cos θo;
  // reflecting about h divides by 4 (wo.h), which cancels.
  const float g1 = 1.0f / (1.0f + view.lambdaWo);
  const float specularPdf = g1 * d / (4.0f * wo.z());
  const float diffusePdf = wi.z() / kPi;
  const float p = view.specularProbability;
  pdf = p * specularPdf + (1.0f - p) * diffusePdf;
  return {diffuse, specular};
}

BsdfLobes PbrBsdf::evalLobes(const Vec3f& wo, const Vec3f& wi) const {
  float pdf;
  return evalLobes(view(wo), wi, pdf);
}

Vec3f PbrBsdf::eval(const Vec3f& wo, const Vec3f& wi) const {
  const BsdfLobes lobes = evalLobes(wo, wi);
  return lobes.diffuse + lobes.specular;
}

float PbrBsdf::pdf(const Vec3f& wo, const Vec3f& wi) const {
  float pdf;
  evalLobes(view(wo), wi, pdf);
  return pdf;
}

std::optional<BsdfSample> PbrBsdf::sample(const View& view, const Vec2f& u, float uLobe, BsdfLobes& lobes) const {
  if (!view.above) return std::nullopt;
  const Vec3f& wo = view.wo;
  const bool specular = uLobe < view.specularProbability;
  Vec3f wi;
  if (specular) {
    const Vec3f h = sampleVisibleNormal(wo, alpha_, u);
    wi = (2.0f * wo.dot(h) * h - wo).normalized();
  } else {
    wi = sampleCosineHemisphere(u);
  }
  // The weight divides by the density of both lobes together (one-sample
  // MIS), which is lower in variance than the picked lobe's alone and is
  // what pdf() returns for the integrator's own MIS.
  float density;
  lobes = evalLobes(view, wi, density);
  if (!(density > 0.0f) || !std::isfinite(density)) return std::nullopt;
  return BsdfSample{wi, (lobes.diffuse + lobes.specular) / density, density, specular};
}

std::optional<BsdfSample> PbrBsdf::sample(const Vec3f& wo, const Vec2f& u, float uLobe) const {
  BsdfLobes lobes;
  return sample(view(wo), u, uLobe, lobes);
}

float PbrBsdf::specularProbability(const Vec3f& wo) const {
  const float cosTheta = std::max(wo.z(), 0.0f);
  const float specular = luminance(schlickFresnel(f0_, f90_, cosTheta));
  const float diffuse = luminance(diffuseColor_);
  return specular + diffuse > 0.0f ? specular / (specular + diffuse) : 1.0f;
}

ShadingFrame ShadingFrame::fromNormal(const Vec3f& n) {
  // Duff et al.'s branch-free form: the sign picks the hemisphere whose
  // formula has no cancellation.
  const float sign = std::copysign(1.0f, n.z());
  const float a = -1.0f / (sign + n.z());
  const float b = n.x() * n.y() * a;
  return {Vec3f(1.0f + sign * n.x() * n.x() * a, sign * b, -sign * n.x()),
          Vec3f(b, sign + n.y() * n.y() * a, -n.y()), n};
}

}  // namespace sdg
