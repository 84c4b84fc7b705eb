// The path tracer's metallic-roughness BSDF: energy (white furnace), the
// sampling density against pdf(), reciprocity, robustness at grazing angles
// and zero roughness, and the shading frame.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <vector>

#include "behavior/rng.h"
#include "render/pathtrace/bsdf.h"

using namespace sdg;

namespace {

constexpr double kPi = 3.14159265358979323846;

Vec3f viewAt(double degrees) {
  const double t = degrees * kPi / 180.0;
  return Vec3f(float(std::sin(t)), 0.0f, float(std::cos(t)));
}

Vec3f randomUnit(Rng& rng) {
  const double z = rng.uniform(-1.0, 1.0), phi = rng.uniform(0.0, 2.0 * kPi), s = std::sqrt(1.0 - z * z);
  return Vec3f(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
}

Vec3f randomUpper(Rng& rng) {
  Vec3f w = randomUnit(rng);
  w.z() = std::abs(w.z());
  return w;
}

Vec2f uniform2(Rng& rng) { return Vec2f(float(rng.uniform01()), float(rng.uniform01())); }

bool finite(const Vec3f& v) { return v.allFinite(); }

// The directional albedo: the mean sample weight over a jittered 64 x 64
// grid (samples that fail count as zero).
float albedo(const PbrBsdf& bsdf, const Vec3f& wo, Rng& rng) {
  constexpr int kSide = 64;
  double sum = 0;
  for (int i = 0; i < kSide; ++i)
    for (int j = 0; j < kSide; ++j) {
      const Vec2f u(float((i + rng.uniform01()) / kSide), float((j + rng.uniform01()) / kSide));
      if (const auto s = bsdf.sample(wo, u, float(rng.uniform01()))) sum += s->weight.maxCoeff();
    }
  return float(sum / (kSide * kSide));
}

// The upper hemisphere cut into nz x nphi cells of equal solid angle (z =
// cos θ uniform); cell (i, j) covers z in [i, i+1) / nz, φ in [j, j+1) 2π / nphi.
struct HemisphereGrid {
  int nz, nphi;
  int cellOf(const Vec3f& w) const {
    double phi = std::atan2(double(w.y()), double(w.x()));
    if (phi < 0) phi += 2.0 * kPi;
    const int i = std::min(int(double(w.z()) * nz), nz - 1);
    const int j = std::min(int(phi / (2.0 * kPi) * nphi), nphi - 1);
    return i * nphi + j;
  }
  // ∫ f dω over every cell, by the midpoint rule with sub x sub points per cell.
  std::vector<double> integrate(const std::function<double(const Vec3f&)>& f, int sub) const {
    std::vector<double> cells(size_t(nz * nphi), 0.0);
    const int nzFine = nz * sub, nphiFine = nphi * sub;
    const double cellArea = 2.0 * kPi / (double(nzFine) * nphiFine);
    for (int a = 0; a < nzFine; ++a)
      for (int b = 0; b < nphiFine; ++b) {
        const double z = (a + 0.5) / nzFine, phi = 2.0 * kPi * (b + 0.5) / nphiFine, s = std::sqrt(1.0 - z * z);
        const Vec3f w(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
        cells[size_t((a / sub) * nphi + b / sub)] += f(w) * cellArea;
      }
    return cells;
  }
};

struct Case {
  PbrMaterial material;
  double viewDegrees;
};

// Materials rough enough for a coarse quadrature to resolve their lobes.
const Case kRoughCases[] = {
    {{Vec3f(1.0f, 1.0f, 1.0f), 0.0f, 0.5f}, 45.0},
    {{Vec3f(0.9f, 0.6f, 0.3f), 1.0f, 0.5f}, 60.0},
    {{Vec3f(0.8f, 0.3f, 0.1f), 0.5f, 1.0f}, 20.0},
    {{Vec3f(0.1f, 0.1f, 0.1f), 0.0f, 0.75f}, 80.0},
};

}  // namespace

TEST_CASE("bsdf: white furnace, the directional albedo stays between its floor and 1", "[pathtrace][bsdf]") {
  // Floors: single-scattering GGX loses energy with roughness, most at
  // roughness 1 (alpha 1) head-on for a metal (bsdf.h gives the figures);
  // each floor is the lowest albedo over the views below less 2-3 %.
  const float roughness[] = {0.05f, 0.1f, 0.25f, 0.5f, 0.75f, 1.0f};
  const float metalFloor[] = {0.98f, 0.97f, 0.87f, 0.82f, 0.60f, 0.29f};
  Rng rng(1, 1);
  for (int r = 0; r < 6; ++r)
    for (double degrees : {0.0, 30.0, 60.0, 75.0, 85.0}) {
      const float metal = albedo(PbrBsdf({Vec3f::Ones(), 1.0f, roughness[r]}), viewAt(degrees), rng);
      // specular_level 0: a dielectric without a coat is Lambert exactly.
      const float lambert = albedo(PbrBsdf({Vec3f::Ones(), 0.0f, roughness[r], 0.0f}), viewAt(degrees), rng);
      // The default coat adds its reflection to the base's full albedo, as
      // the rasterizer and Blender's Principled BSDF do: never less than
      // the base, at most the coat's Fresnel more.
      const float coated = albedo(PbrBsdf({Vec3f::Ones(), 0.0f, roughness[r]}), viewAt(degrees), rng);
      const float fresnel = 0.04f + 0.96f * std::pow(1.0f - std::cos(float(degrees * kPi / 180.0)), 5.0f);
      INFO("roughness " << roughness[r] << ", view " << degrees << "°: metal " << metal << ", lambert " << lambert
                        << ", coated " << coated);
      // A white metal's weights are F G2 / G1 <= 1 one by one.
      CHECK(metal <= 1.0f + 1e-5f);
      CHECK(metal >= metalFloor[r]);
      CHECK(lambert == Approx(1.0f).epsilon(0.01));
      CHECK(coated >= 0.99f);
      CHECK(coated <= 1.01f + fresnel);
    }
  // Head-on, a smooth white dielectric returns its base plus its coat's 4 %.
  CHECK(albedo(PbrBsdf({Vec3f::Ones(), 0.0f, 0.1f}), viewAt(0.0), rng) == Approx(1.04).epsilon(0.01));
}

TEST_CASE("bsdf: a sample's weight is eval / pdf and its pdf is pdf()", "[pathtrace][bsdf]") {
  Rng rng(2, 2);
  for (int n = 0; n < 20000; ++n) {
    const PbrMaterial material{Vec3f(float(rng.uniform01()), float(rng.uniform01()), float(rng.uniform01())),
                               float(rng.uniform01()), float(rng.uniform01())};
    const PbrBsdf bsdf(material);
    const Vec3f wo = randomUpper(rng);
    const auto s = bsdf.sample(wo, uniform2(rng), float(rng.uniform01()));
    if (!s) continue;
    const float pdf = bsdf.pdf(wo, s->wi);
    const Vec3f expected = bsdf.eval(wo, s->wi) / pdf;
    CHECK(s->pdf == Approx(pdf).epsilon(1e-5));
    CHECK(s->wi.norm() == Approx(1.0f).epsilon(1e-5));
    for (int c = 0; c < 3; ++c) CHECK(s->weight[c] == Approx(expected[c]).epsilon(1e-4).margin(1e-7));
  }
}

TEST_CASE("bsdf: the pdf integrates to the share of samples that stay above the surface, at most 1",
          "[pathtrace][bsdf]") {
  const HemisphereGrid grid{64, 128};
  Rng rng(3, 3);
  for (const Case& c : kRoughCases) {
    const PbrBsdf bsdf(c.material);
    const Vec3f wo = viewAt(c.viewDegrees);
    double integral = 0;
    for (double cell : grid.integrate([&](const Vec3f& wi) { return bsdf.pdf(wo, wi); }, 4)) integral += cell;
    int kept = 0;
    constexpr int kSamples = 40000;
    for (int n = 0; n < kSamples; ++n) kept += bsdf.sample(wo, uniform2(rng), float(rng.uniform01())).has_value();
    INFO("roughness " << c.material.roughness << ", view " << c.viewDegrees << "°");
    CHECK(integral <= 1.0 + 1e-3);
    CHECK(integral == Approx(double(kept) / kSamples).margin(0.01));
  }
}

TEST_CASE("bsdf: sampled directions follow pdf() (chi-square on a coarse grid)", "[pathtrace][bsdf]") {
  const HemisphereGrid grid{8, 16};
  Rng rng(4, 4);
  for (const Case& c : kRoughCases) {
    const PbrBsdf bsdf(c.material);
    const Vec3f wo = viewAt(c.viewDegrees);
    constexpr int kSamples = 100000;
    std::vector<double> expected = grid.integrate([&](const Vec3f& wi) { return bsdf.pdf(wo, wi); }, 32);
    double below = 1.0;
    for (double& e : expected) below -= e, e *= kSamples;
    expected.push_back(below * kSamples);  // the last bucket: samples lost below the surface
    std::vector<double> observed(expected.size(), 0.0);
    for (int n = 0; n < kSamples; ++n) {
      const auto s = bsdf.sample(wo, uniform2(rng), float(rng.uniform01()));
      observed[s ? size_t(grid.cellOf(s->wi)) : expected.size() - 1] += 1.0;
    }
    // Pearson's statistic over buckets expecting >= 5 samples; the rest
    // pooled into one.
    double chi2 = 0, pooledExpected = 0, pooledObserved = 0;
    int buckets = 0;
    for (size_t b = 0; b < expected.size(); ++b) {
      if (expected[b] < 5.0) {
        pooledExpected += expected[b], pooledObserved += observed[b];
        continue;
      }
      chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
      ++buckets;
    }
    if (pooledExpected >= 5.0) {
      chi2 += (pooledObserved - pooledExpected) * (pooledObserved - pooledExpected) / pooledExpected;
      ++buckets;
    } else {
      CHECK(pooledObserved <= 15.0);
    }
    const double dof = buckets - 1;
    INFO("roughness " << c.material.roughness << ", view " << c.viewDegrees << "°: chi2 " << chi2 << " over " << dof
                      << " degrees of freedom");
    CHECK(chi2 < dof + 5.0 * std::sqrt(2.0 * dof));
  }
}

TEST_CASE("bsdf: reciprocity, f(wo, wi) = f(wi, wo)", "[pathtrace][bsdf]") {
  Rng rng(5, 5);
  for (int n = 0; n < 20000; ++n) {
    const PbrBsdf bsdf({Vec3f(float(rng.uniform01()), float(rng.uniform01()), float(rng.uniform01())),
                        float(rng.uniform01()), float(rng.uniform01())});
    const Vec3f wo = randomUpper(rng), wi = randomUpper(rng);
    if (wo.z() < 1e-3f || wi.z() < 1e-3f) continue;
    const Vec3f forward = bsdf.eval(wo, wi) / wi.z(), backward = bsdf.eval(wi, wo) / wo.z();
    for (int c = 0; c < 3; ++c) CHECK(forward[c] == Approx(backward[c]).epsilon(1e-4));
  }
}

TEST_CASE("bsdf: finite everywhere, grazing and below the surface included", "[pathtrace][bsdf]") {
  Rng rng(6, 6);
  const float cosines[] = {-0.5f, -1e-7f, 0.0f, 1e-7f, 1e-6f, 2e-6f, 1e-5f, 1e-3f, 0.3f, 1.0f};
  const float roughnesses[] = {0.0f, 1e-4f, 0.01f, 0.05f, 0.5f, 1.0f};
  const float lobeChoices[] = {0.0f, 0.5f, 0.99999994f};
  auto withCos = [&](float z) {
    const float s = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const double phi = rng.uniform(0.0, 2.0 * kPi);
    return Vec3f(s * float(std::cos(phi)), s * float(std::sin(phi)), z);
  };
  for (float roughness : roughnesses)
    for (float metallic : {0.0f, 0.5f, 1.0f})
      for (float base : {0.0f, 0.5f, 1.0f}) {
        const PbrBsdf bsdf({Vec3f::Constant(base), metallic, roughness});
        for (float zo : cosines)
          for (float zi : cosines) {
            const Vec3f wo = withCos(zo), wi = withCos(zi);
            const Vec3f f = bsdf.eval(wo, wi);
            const float pdf = bsdf.pdf(wo, wi);
            CHECK((finite(f) && f.minCoeff() >= 0.0f));
            CHECK((std::isfinite(pdf) && pdf >= 0.0f));
            CHECK(((zo > 1e-6f && zi > 1e-6f) || (f.isZero() && pdf == 0.0f)));
            for (const Vec2f& u : {Vec2f(0, 0), Vec2f(0.99999994f, 0.99999994f), Vec2f(0.5f, 0.5f), uniform2(rng)})
              for (float lobe : lobeChoices)
                if (const auto s = bsdf.sample(wo, u, lobe)) {
                  CHECK((finite(s->wi) && finite(s->weight) && s->weight.minCoeff() >= 0.0f));
                  CHECK((std::isfinite(s->pdf) && s->pdf > 0.0f && s->wi.z() > 0.0f));
                }
          }
      }
}

TEST_CASE("bsdf: roughness 0 reflects as a mirror with the Fresnel weight", "[pathtrace][bsdf]") {
  const Vec3f wo = viewAt(30.0);
  const Vec3f mirror(-wo.x(), -wo.y(), wo.z());
  const PbrBsdf gold({Vec3f(1.0f, 0.8f, 0.3f), 1.0f, 0.0f});
  Rng rng(7, 7);
  // GGX's tails are long: P(θh > t) = 1 / (1 + tan^2 t / alpha^2), so about
  // 1 % of the half vectors lie beyond 10 alpha and 0.04 % beyond 50 alpha.
  int nearMirror = 0;
  for (int n = 0; n < 100; ++n) {
    const auto s = gold.sample(wo, uniform2(rng), float(rng.uniform01()));
    REQUIRE(s);
    CHECK(s->specular);
    nearMirror += s->wi.dot(mirror) > std::cos(0.02f);
    CHECK(s->wi.dot(mirror) > std::cos(0.1f));
    // Schlick at 30°: F0 + (1 - F0) (1 - cos 30°)^5; G2 / G1 is 1 to within 1e-3.
    const float w = std::pow(1.0f - std::cos(float(kPi) / 6.0f), 5.0f);
    CHECK(s->weight.x() == Approx(1.0f).margin(2e-3));
    CHECK(s->weight.y() == Approx(0.8f + 0.2f * w).margin(2e-3));
    CHECK(s->weight.z() == Approx(0.3f + 0.7f * w).margin(2e-3));
  }
  CHECK(nearMirror >= 95);
  // A dielectric mixes its lobes by their Fresnel estimate: mostly diffuse
  // head-on, about half specular at grazing.
  const PbrBsdf plastic({Vec3f::Constant(0.8f), 0.0f, 0.0f});
  CHECK(plastic.specularProbability(viewAt(0.0)) < 0.1f);
  CHECK(plastic.specularProbability(viewAt(89.0)) > 0.5f);
  CHECK(PbrBsdf({Vec3f::Constant(0.8f), 1.0f, 0.3f}).specularProbability(viewAt(0.0)) == 1.0f);
}

TEST_CASE("bsdf: the shading frame is orthonormal, right-handed and maps n to +Z", "[pathtrace][bsdf]") {
  Rng rng(8, 8);
  std::vector<Vec3f> normals = {Vec3f(0, 0, 1), Vec3f(0, 0, -1), Vec3f(1, 0, 0), Vec3f(0, -1, 0),
                                Vec3f(0.0f, 1e-4f, -1.0f).normalized(), Vec3f(1e-7f, 0.0f, -1.0f).normalized()};
  for (int n = 0; n < 1000; ++n) normals.push_back(randomUnit(rng));
  for (const Vec3f& n : normals) {
    const ShadingFrame frame = ShadingFrame::fromNormal(n);
    INFO("n = " << n.transpose());
    CHECK(frame.s.norm() == Approx(1.0f).epsilon(1e-5));
    CHECK(frame.t.norm() == Approx(1.0f).epsilon(1e-5));
    CHECK(std::abs(frame.s.dot(frame.t)) < 1e-5f);
    CHECK(std::abs(frame.s.dot(n)) < 1e-5f);
    CHECK(std::abs(frame.t.dot(n)) < 1e-5f);
    CHECK((frame.s.cross(frame.t) - n).norm() < 1e-5f);
    CHECK((frame.toLocal(n) - Vec3f(0, 0, 1)).norm() < 1e-5f);
    const Vec3f v = randomUnit(rng);
    CHECK((frame.toWorld(frame.toLocal(v)) - v).norm() < 1e-5f);
  }
}
