// The path tracer's light transport against analytic answers: a white
// furnace, a sphere light's irradiance, the multiple bounces inside a
// closed sphere, GGX's energy, each light type's radiometry against the
// rasterizer's definitions, and the 1/sqrt(N) convergence of the error.
//
// The expected values use the BSDF itself (bsdf.h) through deterministic
// quadratures, not a Lambertian idealisation: the surface model has a 4 %
// dielectric coat whose Fresnel terms make even a "diffuse" material
// depart from rho / pi by several per cent. So these tests check the
// transport (cameras, lights, sampling, MIS, roulette, bounces); the BSDF
// has its own tests.
#include "pt_test_scenes.h"

#include "render/pathtrace/pt_lights.h"

#include <numeric>

using namespace sdg;
using namespace sdg::pttest;

namespace {

// Mean of `value` over the pixels whose 3 x 3 neighbourhood is all on
// instance `id`: silhouette pixels mix the object and what is behind it.
template <typename Fn>
double interiorMean(const PathTracedFrame& f, uint32_t id, Fn value, int* count = nullptr) {
  double sum = 0;
  int n = 0;
  for (int y = 1; y < f.height - 1; ++y)
    for (int x = 1; x < f.width - 1; ++x) {
      bool inside = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) inside = inside && f.instance[size_t((y + dy) * f.width + x + dx)] == id;
      if (!inside) continue;
      sum += value(size_t(y * f.width + x));
      ++n;
    }
  if (count) *count = n;
  return n ? sum / n : 0.0;
}

// Linear interpolation in a table of f(mu) on mu = 0, 1/(n-1), ..., 1.
double lookup(const std::vector<double>& table, double mu) {
  const double s = std::clamp(mu, 0.0, 1.0) * double(table.size() - 1);
  const size_t i = std::min(size_t(s), table.size() - 2);
  return table[i] + (table[i + 1] - table[i]) * (s - double(i));
}

std::vector<double> albedoTable(const PbrBsdf& bsdf, int n = 65) {
  std::vector<double> table;
  for (int i = 0; i < n; ++i) table.push_back(directionalAlbedo(bsdf, std::max(double(i) / (n - 1), 1e-4)));
  return table;
}

// An orthographic camera looking down -Z from +Z (16 units wide): a furnace
// object fills most of the image.
const char* kTopCamera =
    "  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 26, translate: [0, 0, 10], clippingRange: [0.1, 100]}\n";

std::string sphereScene(const std::string& material, const std::string& lights) {
  return "version: 1\nprims:\n  /Looks: {type: Scope}\n  /Looks/M: {type: Material, " + material +
         "}\n  /Ball: {type: Mesh, asset: " + fineSphereObj() + ", material: /Looks/M}\n" + lights + kTopCamera;
}

}  // namespace

TEST_CASE("path tracer: a diffuse sphere in a uniform dome returns the BSDF's directional albedo times L (white furnace)",
          "[pathtrace]") {
  const float L = 2.0f;
  const RenderList list = renderListOf(sphereScene(
      "inputs:diffuse_color_constant: [0.5, 0.5, 0.5], inputs:reflection_roughness_constant: 1.0, inputs:metallic_constant: 0",
      "  /Sky: {type: DomeLight, inputs:intensity: 2}\n"));
  PathTraceSettings settings;
  settings.samples = 32;
  settings.maxBounces = 8;
  const PathTracedFrame f = trace(list, 32, 32, settings);
  // A convex object in a furnace: every pixel sees one bounce, so its
  // value is L times the directional albedo at its view cosine (the view
  // is +Z everywhere: the camera is orthographic).
  const std::vector<double> albedo = albedoTable(PbrBsdf(PbrMaterial{Vec3f::Constant(0.5f), 0.0f, 1.0f}));
  int pixels = 0;
  const double rendered = interiorMean(f, 1, [&](size_t p) { return f.radiance[3 * p]; }, &pixels);
  const double expected = interiorMean(f, 1, [&](size_t p) { return L * lookup(albedo, f.normal[3 * p + 2]); });
  INFO("pixels " << pixels << ", rendered " << rendered << ", expected " << expected << ", rho L " << 0.5 * L);
  REQUIRE(pixels > 300);
  CHECK(std::abs(rendered / expected - 1.0) < 0.01);
  // The background is the dome itself.
  CHECK(f.radiance[0] == Approx(L).epsilon(1e-6));
}

TEST_CASE("path tracer: a sphere light lights a plane with its analytic irradiance pi L sin^2(alpha)", "[pathtrace]") {
  // A matte plane at z = 0, a sphere light of radius 0.5 two units above
  // the origin (sin alpha = 1/4), an orthographic camera 45 degrees off
  // the normal seeing a 0.4-unit patch around the origin.
  const float radiance = 100.0f, radius = 0.5f, height = 2.0f;
  const std::string yaml = R"(version: 1
prims:
  /Looks: {type: Scope}
  /Looks/M: {type: Material, inputs:diffuse_color_constant: [0.5, 0.5, 0.5], inputs:reflection_roughness_constant: 1.0}
  /Floor: {type: Plane, width: 20, length: 20, material: /Looks/M}
  /Lamp: {type: SphereLight, inputs:radius: 0.5, inputs:intensity: 100, translate: [0, 0, 2]}
  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 4, translate: [0, -7.0710678, 7.0710678], rotateXYZ: [45, 0, 0], clippingRange: [0.1, 100]}
)";
  const RenderList list = renderListOf(yaml);
  PathTraceSettings settings;
  settings.samples = 256;
  settings.maxBounces = 8;
  const int size = 16;
  const PathTracedFrame f = trace(list, size, size, settings);
  double rendered = 0;
  for (int y = 6; y < 10; ++y)
    for (int x = 6; x < 10; ++x) rendered += f.radiance[3 * size_t(y * size + x)] / 16.0;
  // Outgoing radiance: L times the integral of f cos over the light's cone
  // (it is centred on the normal), for the view 45 degrees off.
  const PbrBsdf bsdf(PbrMaterial{Vec3f::Constant(0.5f), 0.0f, 1.0f});
  const double sinAlpha = radius / height, cosAlpha = std::sqrt(1 - sinAlpha * sinAlpha);
  std::vector<double> mu, w;
  gaussLegendre(32, cosAlpha, 1.0, mu, w);
  double integral = 0;
  for (size_t k = 0; k < mu.size(); ++k) integral += w[k] * azimuthIntegral(bsdf, std::sqrt(0.5), mu[k]);
  const double expected = radiance * integral;
  const double irradiance = kPi * radiance * sinAlpha * sinAlpha;
  INFO("rendered " << rendered << ", expected " << expected << " (E = " << irradiance << ", rho E / pi = "
                   << 0.5 * irradiance / kPi << ")");
  CHECK(std::abs(rendered / expected - 1.0) < 0.01);
  // The patch's neighbours at 0.1 units: the same within the falloff.
  CHECK(f.instance[size_t(8 * size + 8)] == 1u);
}

TEST_CASE("path tracer: inside a closed sphere lit from its centre, the multiple bounces give the integral equation's solution",
          "[pathtrace]") {
  // The wall's radiance depends only on the view cosine mu, by symmetry,
  // and a chord leaves and meets the sphere at the same angle, so the
  // light arriving at angle mu is the light leaving at mu, or the lamp's
  // radiance inside its cone (mu > cos alpha):
  //   L(mu) = Le int_{cos a}^1 K(mu, m) dm + int_0^{cos a} K(mu, m) L(m) dm,
  // K(mu, m) = int f cos dphi. Solved by Nystrom's method on Gauss-Legendre
  // nodes: exact up to quadrature, for this BSDF (no Lambertian idealisation).
  const double Le = 50.0, r = 0.1, rho = 0.7;
  const std::string yaml = "version: 1\nprims:\n  /Looks: {type: Scope}\n"
                           "  /Looks/M: {type: Material, inputs:diffuse_color_constant: [0.7, 0.7, 0.7], inputs:reflection_roughness_constant: 1.0}\n"
                           "  /Room: {type: Mesh, asset: " + fineSphereObj() + ", material: /Looks/M}\n"
                           "  /Lamp: {type: SphereLight, inputs:radius: 0.1, inputs:intensity: 50}\n"
                           "  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 8, translate: [0, 0, -0.3], clippingRange: [0.01, 10]}\n";
  const RenderList list = renderListOf(yaml);
  PathTraceSettings settings;
  settings.samples = 64;
  settings.maxBounces = 100;  // the series, not its first 8 terms
  const PathTracedFrame f = trace(list, 16, 16, settings);

  const PbrBsdf bsdf(PbrMaterial{Vec3f::Constant(float(rho)), 0.0f, 1.0f});
  const double cosAlpha = std::sqrt(1 - r * r);
  std::vector<double> mu, w, muLamp, wLamp;
  gaussLegendre(48, 0.0, cosAlpha, mu, w);
  gaussLegendre(16, cosAlpha, 1.0, muLamp, wLamp);
  auto direct = [&](double muO) {
    double sum = 0;
    for (size_t k = 0; k < muLamp.size(); ++k) sum += wLamp[k] * azimuthIntegral(bsdf, muO, muLamp[k]);
    return Le * sum;
  };
  const size_t n = mu.size();
  // (I - K W) L = g, by Gaussian elimination.
  std::vector<double> a(n * n), g(n);
  for (size_t i = 0; i < n; ++i) {
    g[i] = direct(mu[i]);
    for (size_t j = 0; j < n; ++j) a[i * n + j] = (i == j ? 1.0 : 0.0) - w[j] * azimuthIntegral(bsdf, mu[i], mu[j]);
  }
  for (size_t c = 0; c < n; ++c)
    for (size_t i = c + 1; i < n; ++i) {
      const double m = a[i * n + c] / a[c * n + c];
      for (size_t j = c; j < n; ++j) a[i * n + j] -= m * a[c * n + j];
      g[i] -= m * g[c];
    }
  std::vector<double> solution(n);
  for (size_t i = n; i-- > 0;) {
    double s = g[i];
    for (size_t j = i + 1; j < n; ++j) s -= a[i * n + j] * solution[j];
    solution[i] = s / a[i * n + i];
  }
  auto wall = [&](double muO) {  // Nystrom's interpolation
    double s = direct(muO);
    for (size_t j = 0; j < n; ++j) s += w[j] * azimuthIntegral(bsdf, muO, mu[j]) * solution[j];
    return s;
  };
  // Every pixel sees the wall (the camera looks down -Z, away from the
  // lamp); its view cosine is the normal's z.
  double rendered = 0, expected = 0, single = 0;
  for (size_t p = 0; p < f.instance.size(); ++p) {
    REQUIRE(f.instance[p] == 1u);
    rendered += f.radiance[3 * p];
    expected += wall(f.normal[3 * p + 2]);
    single += direct(f.normal[3 * p + 2]);
  }
  INFO("rendered " << rendered / 256 << ", expected " << expected / 256 << ", direct only " << single / 256);
  CHECK(std::abs(rendered / expected - 1.0) < 0.02);
  CHECK(expected > 1.5 * single);  // the bounces matter here
}

TEST_CASE("path tracer: GGX metal keeps at most the light it receives (furnace, roughness 0.1, 0.5, 1)", "[pathtrace]") {
  for (float roughness : {0.1f, 0.5f, 1.0f}) {
    INFO("roughness " << roughness);
    const RenderList list = renderListOf(sphereScene(
        "inputs:diffuse_color_constant: [1, 1, 1], inputs:metallic_constant: 1, inputs:reflection_roughness_constant: " +
            std::to_string(roughness),
        "  /Sky: {type: DomeLight, inputs:intensity: 1}\n"));
    PathTraceSettings settings;
    settings.samples = 64;
    settings.maxBounces = 8;
    const PathTracedFrame f = trace(list, 32, 32, settings);
    int pixels = 0;
    const double mean = interiorMean(f, 1, [&](size_t p) { return f.radiance[3 * p]; }, &pixels);
    double brightest = 0;
    interiorMean(f, 1, [&](size_t p) { return brightest = std::max(brightest, double(f.radiance[3 * p])), 0.0; });
    REQUIRE(pixels > 300);
    // Single-scattering GGX loses energy, never gains it: the mean stays
    // at or below L = 1 (within its noise, about 2e-4 here) and no pixel
    // rises above it by more than its own noise (about 1 % at 64 samples).
    INFO("mean " << mean << ", brightest pixel " << brightest);
    CHECK(mean <= 1.001);
    CHECK(brightest <= 1.03);
    if (roughness == 0.1f) {
      CHECK(mean > 0.99);  // bsdf.h: >= 99 % kept at roughness 0.1
    } else {
      // Smooth enough lobes for the quadrature: the albedo at each pixel's
      // view cosine, as in the white furnace above.
      const std::vector<double> albedo = albedoTable(PbrBsdf(PbrMaterial{Vec3f::Ones(), 1.0f, roughness}));
      const double expected = interiorMean(f, 1, [&](size_t p) { return lookup(albedo, f.normal[3 * p + 2]); });
      INFO("expected " << expected);
      CHECK(std::abs(mean / expected - 1.0) < 0.01);
    }
  }
}

TEST_CASE("path tracer: rect, disk, cylinder and distant lights give their exact irradiance and the rasterizer's",
          "[pathtrace]") {
  // A matte plane (normal +Z) seen by the 45-degree orthographic camera of
  // the sphere light test, lit by one light at a time. Expected: the
  // outgoing radiance at the origin integrated over the light's emitting
  // surface (or cone) by quadrature, f L cos cos' / d^2 dA; and, within the
  // small-light error, the rasterizer's formula (L A cos' / d^2; E for a
  // distant light) times f.
  const double L = 1000;
  const PbrBsdf bsdf(PbrMaterial{Vec3f::Constant(0.5f), 0.0f, 1.0f});
  const Vec3f wo = Vec3f(0.0f, -1.0f, 1.0f).normalized();
  // f L cos cos' / d^2 for a surface element at q with outward normal m and area dA.
  auto element = [&](const Vec3d& q, const Vec3d& m, double area) {
    const double d2 = q.squaredNorm();
    const Vec3d wi = q / std::sqrt(d2);
    const double cosLight = -m.dot(wi);
    if (cosLight <= 0 || wi.z() <= 0) return 0.0;
    return double(bsdf.eval(wo, wi.cast<float>()).x()) * L * cosLight / d2 * area;  // eval is f cos
  };
  auto rect = [&](double w, double h, double z) {
    double sum = 0;
    const int n = 64;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        sum += element({(i + 0.5) / n * w - w / 2, (j + 0.5) / n * h - h / 2, z}, {0, 0, -1}, w * h / (n * n));
    return sum;
  };
  auto disk = [&](double r, double z) {
    double sum = 0;
    const int n = 64, m = 128;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j) {
        const double rho = r * std::sqrt((i + 0.5) / n), phi = 2 * kPi * (j + 0.5) / m;  // equal areas
        sum += element({rho * std::cos(phi), rho * std::sin(phi), z}, {0, 0, -1}, kPi * r * r / (n * m));
      }
    return sum;
  };
  auto cylinder = [&](double r, double length, const Vec3d& centre) {
    double sum = 0;
    const int n = 64, m = 512;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j) {
        const double x = (i + 0.5) / n * length - length / 2, phi = 2 * kPi * (j + 0.5) / m;
        const Vec3d normal(0, std::cos(phi), std::sin(phi));
        sum += element(centre + Vec3d(x, 0, 0) + r * normal, normal, 2 * kPi * r * length / (n * m));
      }
    return sum;
  };
  // A cone of half-angle g around the normal, of radiance E / (pi sin^2 g).
  auto cone = [&](double angleDegrees, double E) {
    const double g = angleDegrees / 2 * kPi / 180;
    std::vector<double> mu, w;
    gaussLegendre(16, std::cos(g), 1.0, mu, w);
    double sum = 0;
    for (size_t k = 0; k < mu.size(); ++k) sum += w[k] * azimuthIntegral(bsdf, std::sqrt(0.5), mu[k]);
    return E / (kPi * std::sin(g) * std::sin(g)) * sum;
  };
  const double fNormal = bsdf.eval(wo, Vec3f(0, 0, 1)).x();  // f at normal incidence (cos = 1)
  const Vec3f towardCylinder = Vec3f(0, 1, 4).normalized();
  const double fCylinder = bsdf.eval(wo, towardCylinder).x() / towardCylinder.z();
  struct Case {
    const char* name;
    std::string light;
    double exact;      // the quadrature
    double rasterizer; // the rasterizer's irradiance times f
  };
  const std::vector<Case> cases = {
      {"rect", "{type: RectLight, inputs:width: 0.2, inputs:height: 0.3, inputs:intensity: 1000, translate: [0, 0, 4]}",
       rect(0.2, 0.3, 4), fNormal * L * 0.2 * 0.3 / 16},
      {"disk", "{type: DiskLight, inputs:radius: 0.15, inputs:intensity: 1000, translate: [0, 0, 4]}", disk(0.15, 4),
       fNormal * L * kPi * 0.15 * 0.15 / 16},
      // Along X, seen from the side: the rasterizer's projected area 2 r length.
      {"cylinder", "{type: CylinderLight, inputs:radius: 0.05, inputs:length: 0.4, inputs:intensity: 1000, translate: [0, 1, 4]}",
       cylinder(0.05, 0.4, {0, 1, 4}), fCylinder * L * 2 * 0.05 * 0.4 / 17 * towardCylinder.z()},
      {"distant, delta", "{type: DistantLight, inputs:angle: 0, inputs:intensity: 3}", fNormal * 3, fNormal * 3},
      {"distant, 10 degrees", "{type: DistantLight, inputs:angle: 10, inputs:intensity: 3}", cone(10, 3), fNormal * 3},
      {"distant, 0.53 degrees", "{type: DistantLight, inputs:intensity: 3}", cone(0.53, 3), fNormal * 3},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    const std::string yaml = std::string(R"(version: 1
prims:
  /Looks: {type: Scope}
  /Looks/M: {type: Material, inputs:diffuse_color_constant: [0.5, 0.5, 0.5], inputs:reflection_roughness_constant: 1.0}
  /Floor: {type: Plane, width: 20, length: 20, material: /Looks/M}
  /Light: )") + c.light + R"(
  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 4, translate: [0, -7.0710678, 7.0710678], rotateXYZ: [45, 0, 0], clippingRange: [0.1, 100]}
)";
    PathTraceSettings settings;
    settings.samples = 64;
    settings.maxBounces = 8;
    const PathTracedFrame f = trace(renderListOf(yaml), 16, 16, settings);
    double rendered = 0;
    for (int y = 6; y < 10; ++y)
      for (int x = 6; x < 10; ++x) rendered += f.radiance[3 * size_t(y * 16 + x)] / 16.0;
    INFO("rendered " << rendered << ", exact " << c.exact << ", rasterizer's " << c.rasterizer);
    CHECK(std::abs(rendered / c.exact - 1.0) < 0.01);
    // The point-light formula is within 1 % at these sizes and distances.
    CHECK(std::abs(c.exact / c.rasterizer - 1.0) < 0.01);
  }
}

TEST_CASE("path tracer: the error against a reference falls as 1/sqrt(N)", "[pathtrace]") {
  const RenderList list = renderListOf(R"(version: 1
prims:
  /Looks: {type: Scope}
  /Looks/White: {type: Material, inputs:diffuse_color_constant: [0.73, 0.73, 0.73], inputs:reflection_roughness_constant: 1.0}
  /Looks/Red: {type: Material, inputs:diffuse_color_constant: [0.63, 0.065, 0.05], inputs:reflection_roughness_constant: 1.0}
  /Looks/Glossy: {type: Material, inputs:diffuse_color_constant: [0.8, 0.8, 0.8], inputs:reflection_roughness_constant: 0.3, inputs:metallic_constant: 1}
  /Floor: {type: Plane, width: 2, length: 2, material: /Looks/White}
  /Ceiling: {type: Plane, width: 2, length: 2, translate: [0, 0, 2], material: /Looks/White}
  /Back: {type: Plane, axis: Y, width: 2, length: 2, translate: [0, 1, 1], material: /Looks/White}
  /Left: {type: Plane, axis: X, width: 2, length: 2, translate: [-1, 0, 1], material: /Looks/Red}
  /Right: {type: Plane, axis: X, width: 2, length: 2, translate: [1, 0, 1], material: /Looks/White}
  /Box: {type: Cube, size: 0.6, translate: [0.3, 0.2, 0.3], rotateZ: 20, material: /Looks/Glossy}
  /Light: {type: SphereLight, inputs:radius: 0.1, inputs:intensity: 2000, translate: [0, 0, 1.6]}
  /Camera: {type: Camera, focalLength: 28.8, clippingRange: [0.1, 100], translate: [0, -3.75, 1], rotateX: 70}
)");
  const int size = 16;
  PathTraceSettings settings;
  settings.samples = 4096;
  settings.maxBounces = 8;
  const PathTracedFrame reference = trace(list, size, size, settings, 999);
  std::vector<double> logN, logError;
  // The mean squared error over 8 independent seeds at each N: one
  // seed's error is dominated by its few brightest paths (the metal box
  // focuses the lamp), whose luck varies more than the trend.
  const int seeds = 8;
  for (int n : {16, 32, 64, 128, 256}) {
    settings.samples = n;
    double squared = 0;
    for (int seed = 0; seed < seeds; ++seed) {
      const PathTracedFrame f = trace(list, size, size, settings, uint64_t(seed) + 1);
      for (size_t i = 0; i < f.radiance.size(); ++i) squared += std::pow(f.radiance[i] - reference.radiance[i], 2);
    }
    const double mse = squared / double(reference.radiance.size() * seeds);
    logN.push_back(std::log(double(n)));
    logError.push_back(0.5 * std::log(mse));
  }
  // Least-squares slope of log(RMSE) against log(N).
  const double mx = std::accumulate(logN.begin(), logN.end(), 0.0) / logN.size();
  const double my = std::accumulate(logError.begin(), logError.end(), 0.0) / logError.size();
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < logN.size(); ++i) {
    sxy += (logN[i] - mx) * (logError[i] - my);
    sxx += (logN[i] - mx) * (logN[i] - mx);
  }
  const double slope = sxy / sxx;
  INFO("slope " << slope << ", RMSE at 16: " << std::exp(logError.front()) << ", at 256: " << std::exp(logError.back()));
  CHECK(slope == Approx(-0.5).margin(0.1));
}

TEST_CASE("path tracer lights: a dome without a map gets no shadow rays, its light comes from escaping paths at full weight",
          "[pathtrace]") {
  // A uniform dome's shadow rays would follow the cosine over the
  // hemisphere, what a diffuse BSDF's own direction draws already: they are
  // left to the other lights (pt_lights.cpp).
  const RenderList list = renderListOf(
      "version: 1\nprims:\n  /Floor: {type: Plane, width: 4, length: 4}\n"
      "  /Sky: {type: DomeLight, inputs:intensity: 3, inputs:color: [1, 0.5, 0.25]}\n"
      "  /Sun: {type: DistantLight, inputs:intensity: 2, inputs:angle: 1, rotateXYZ: [20, 0, 0]}\n");
  PtLights lights;
  lights.build(list, Eigen::AlignedBox3f(Vec3f(-2, -2, 0), Vec3f(2, 2, 0.1f)),
               [](const RenderLight&) -> const PtDomeMap* { return nullptr; });
  REQUIRE(lights.lights().size() == 2);
  int dome = -1, sun = -1;
  for (size_t i = 0; i < lights.lights().size(); ++i)
    (lights.lights()[i].kind == LightKind::Dome ? dome : sun) = int(i);
  REQUIRE(dome >= 0);
  REQUIRE(sun >= 0);
  CHECK(lights.lights()[size_t(dome)].pick == 0.0f);
  CHECK(lights.lights()[size_t(sun)].pick == 1.0f);
  const Vec3f p(0, 0, 0), n(0, 0, 1);
  for (int k = 0; k < 256; ++k) {
    LightSample s;
    if (lights.sample(p, n, (float(k) + 0.5f) / 256.0f, Vec2f(0.3f, 0.7f), s)) CHECK(s.light == sun);
  }
  // A path escaping upward, away from the sun's cone: all of the dome's radiance, whatever the BSDF's density.
  const Vec3f up(0, 0, 1);
  for (float bsdfPdf : {0.05f, 0.3f, 2.0f}) {
    const Vec3f got = lights.escaped(p, n, up, bsdfPdf);
    CHECK(got.x() == Approx(3.0f).epsilon(1e-6));
    CHECK(got.y() == Approx(1.5f).epsilon(1e-6));
    CHECK(got.z() == Approx(0.75f).epsilon(1e-6));
  }
}
