// The CPU path tracer against closed-form answers, on pure Lambertian
// surfaces (specular_level 0: no coat, so f = rho / pi exactly and the
// answers need no quadrature of the BSDF): a rect emitter's irradiance at
// several points, a sphere light's on a plane, the white furnace, the
// multi-bounce mean of a closed box from its power balance, and colour
// bleeding between two coloured halves of a sphere from the two-patch
// radiosity equations (exact inside a sphere, see that test).
//
// Sizes and sample counts are small so that the file runs in a few seconds
// (and under ASan in CI); the tolerances are the (0.5 % direct,
// 1 % multi-bounce), with the noise of these sample counts well inside them.
#include "pt_test_scenes.h"

using namespace sdg;
using namespace sdg::pttest;

namespace {

const char* kLambert = "inputs:reflection_roughness_constant: 1.0, inputs:specular_level: 0";

std::string lambert(double r, double g, double b) {
  return "{type: Material, inputs:diffuse_color_constant: [" + std::to_string(r) + ", " + std::to_string(g) + ", " +
         std::to_string(b) + "], " + kLambert + "}";
}

// A hemisphere of the unit sphere (z >= 0 or z <= 0), as fine as fineSphereObj().
std::string fineHemisphereObj(bool upper) {
  return upper ? sphereZoneObj("upper_hemisphere.obj", 0.0, kPi / 2, 64)
               : sphereZoneObj("lower_hemisphere.obj", kPi / 2, kPi, 64);
}

// The form factor from a point to a parallel rectangle [0, a] x [0, b] at
// height h with a corner straight above it; odd in a and in b, so signed
// corners add up to any parallel rectangle (the standard corner formula).
double cornerFormFactor(double a, double b, double h) {
  const double A = a / h, B = b / h;
  const double sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  return (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2 * kPi);
}

// The mean of fn(u, v) over pixel (x, y)'s square of an orthographic view
// `width` units wide centred on (0, 0) (v up, rows down), by an 8 x 8
// midpoint rule: a pixel's value is its box-filtered mean, not its centre's.
template <typename Fn>
double pixelMean(Fn fn, int x, int y, int pixels, double width) {
  const double pixel = width / pixels;
  double sum = 0;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i)
      sum += fn((x + (i + 0.5) / 8) * pixel - width / 2, width / 2 - (y + (j + 0.5) / 8) * pixel);
  return sum / 64;
}

double meanRed(const PathTracedFrame& f, int x0, int y0, int size) {
  double sum = 0;
  for (int y = y0; y < y0 + size; ++y)
    for (int x = x0; x < x0 + size; ++x) sum += f.radiance[3 * size_t(y * f.width + x)];
  return sum / (size * size);
}

// Checks the mean of each 4 x 4-pixel patch at `corners` of a view
// `width` units wide against the pixels' box-filtered mean of `expected`.
template <typename Fn>
void checkPatches(const PathTracedFrame& f, std::initializer_list<std::pair<int, int>> corners, Fn expected,
                  double width, double tolerance) {
  for (auto [px, py] : corners) {
    double want = 0;
    for (int y = py; y < py + 4; ++y)
      for (int x = px; x < px + 4; ++x) want += pixelMean(expected, x, y, f.width, width) / 16;
    const double got = meanRed(f, px, py, 4);
    INFO("patch (" << px << ", " << py << "): rendered " << got << ", expected " << want);
    CHECK(std::abs(got / want - 1) < tolerance);
  }
}

}  // namespace

TEST_CASE("known answers: a rect emitter's direct irradiance at several points of a plane (corner formula, 0.5 %)",
          "[pathtrace][known]") {
  // A 1 x 2 RectLight one unit above a Lambertian floor (rho 0.5), facing
  // it; the camera looks straight down through the light's back, which
  // lets camera rays pass. Floor point p shows rho L F(p) (Lo = rho E / pi,
  // E = pi L F).
  const double L = 10, rho = 0.5, w = 1, hgt = 2, h = 1;
  const std::string yaml = "version: 1\nprims:\n  /Looks: {type: Scope}\n  /Looks/M: " + lambert(rho, rho, rho) +
                           "\n  /Floor: {type: Plane, width: 20, length: 20, material: /Looks/M}\n"
                           "  /Lamp: {type: RectLight, inputs:width: 1, inputs:height: 2, inputs:intensity: 10, "
                           "translate: [0, 0, 1]}\n"
                           "  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 40, translate: [0, 0, 5], "
                           "clippingRange: [0.1, 100]}\n";
  PathTraceSettings settings;
  settings.samples = 2048;
  settings.maxBounces = 2;
  const int size = 16;  // 4 x 4-pixel patches, each a unit square
  const PathTracedFrame f = trace(renderListOf(yaml), size, size, settings);
  auto expected = [&](double x, double y) {
    auto F = [&](double a, double b) { return cornerFormFactor(a, b, h); };
    const double x1 = -w / 2 - x, x2 = w / 2 - x, y1 = -hgt / 2 - y, y2 = hgt / 2 - y;
    return rho * L * (F(x2, y2) - F(x1, y2) - F(x2, y1) + F(x1, y1));
  };
  // Patches under the lamp, across its edge, beyond its corner, further out.
  checkPatches(f, {{6, 6}, {8, 4}, {12, 0}, {0, 12}}, expected, 4.0, 0.005);
}

TEST_CASE("known answers: a sphere light's irradiance on a facing plane is pi L (r/d)^2 cos (0.5 %)",
          "[pathtrace][known]") {
  // A sphere wholly above a plane's horizon gives E = pi L r^2 cos(theta) / d^2
  // at every point (theta: from the normal to the sphere's centre).
  const double L = 100, r = 0.25, h = 1, rho = 0.5;
  const std::string yaml = "version: 1\nprims:\n  /Looks: {type: Scope}\n  /Looks/M: " + lambert(rho, rho, rho) +
                           "\n  /Floor: {type: Plane, width: 20, length: 20, material: /Looks/M}\n"
                           "  /Lamp: {type: SphereLight, inputs:radius: 0.25, inputs:intensity: 100, translate: [0, 0, 1]}\n"
                           "  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 30, translate: [0, -7.0710678, "
                           "7.0710678], rotateXYZ: [45, 0, 0], clippingRange: [0.1, 100]}\n";
  PathTraceSettings settings;
  settings.samples = 256;
  settings.maxBounces = 1;
  const int size = 16;
  const PathTracedFrame f = trace(renderListOf(yaml), size, size, settings);
  // The 45-degree orthographic camera (3 units wide) sees image point (u, v)
  // at floor point (u, sqrt 2 v).
  auto expected = [&](double u, double v) {
    const double dy = std::sqrt(2.0) * v, d2 = u * u + dy * dy + h * h;
    return rho / kPi * (kPi * L * r * r / d2 * (h / std::sqrt(d2)));
  };
  checkPatches(f, {{6, 6}, {0, 12}, {12, 0}}, expected, 3.0, 0.005);
}

TEST_CASE("known answers: a Lambertian sphere in a uniform dome shows rho L (white furnace)", "[pathtrace][known]") {
  const double L = 2, rho = 0.8;
  const std::string yaml = "version: 1\nprims:\n  /Looks: {type: Scope}\n  /Looks/M: " + lambert(rho, rho, rho) +
                           "\n  /Ball: {type: Mesh, asset: " + fineSphereObj() +
                           ", material: /Looks/M}\n  /Sky: {type: DomeLight, inputs:intensity: 2}\n"
                           "  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 26, translate: [0, 0, 10], "
                           "clippingRange: [0.1, 100]}\n";
  PathTraceSettings settings;
  settings.samples = 16;
  settings.maxBounces = 8;
  const PathTracedFrame f = trace(renderListOf(yaml), 16, 16, settings);
  double sum = 0;
  int n = 0;
  // Pixels whose neighbours are on the ball too: a silhouette pixel's
  // jittered samples also see the sky.
  for (int y = 1; y < f.height - 1; ++y)
    for (int x = 1; x < f.width - 1; ++x) {
      const size_t p = size_t(y * f.width + x);
      if (f.instance[p] != 1u || f.instance[p - 1] != 1u || f.instance[p + 1] != 1u ||
          f.instance[p - size_t(f.width)] != 1u || f.instance[p + size_t(f.width)] != 1u)
        continue;
      sum += f.radiance[3 * p];
      ++n;
    }
  REQUIRE(n > 50);
  INFO("mean " << sum / n << " over " << n << " pixels, expected " << rho * L);
  CHECK(std::abs(sum / n / (rho * L) - 1) < 0.005);
}

TEST_CASE("known answers: a closed diffuse box lit inside keeps its power balance (multi-bounce mean, 1 %)",
          "[pathtrace][known]") {
  // A cube of side 2 (area A = 24), rho 0.5, a sphere light of radius r at
  // its centre: power Phi = pi L 4 pi r^2. Reflected light leaves the walls
  // diffusely and a fraction f = 4 pi r^2 / A of it (the walls' form factor
  // to the lamp, by reciprocity) is stopped by the lamp, so the walls
  // receive P = Phi / (1 - rho (1 - f)) in all, and their mean radiance is
  // rho P / (pi A). By symmetry each face has that mean: the camera looks at
  // the whole floor face from just below the lamp.
  const double L = 20, r = 0.1, rho = 0.5, A = 24;
  const std::string yaml = "version: 1\nprims:\n  /Looks: {type: Scope}\n  /Looks/M: " + lambert(rho, rho, rho) +
                           "\n  /Box: {type: Cube, size: 2, material: /Looks/M}\n"
                           "  /Lamp: {type: SphereLight, inputs:radius: 0.1, inputs:intensity: 20}\n"
                           "  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 20, translate: [0, 0, -0.2], "
                           "clippingRange: [0.01, 10]}\n";
  PathTraceSettings settings;
  settings.samples = 128;
  settings.maxBounces = 64;
  const PathTracedFrame f = trace(renderListOf(yaml), 16, 16, settings);
  const double phi = kPi * L * 4 * kPi * r * r, lost = 4 * kPi * r * r / A;
  const double expected = rho * phi / (1 - rho * (1 - lost)) / (kPi * A);
  const double direct = rho * phi / (kPi * A);
  const double got = meanRed(f, 0, 0, 16);
  INFO("rendered " << got << ", expected " << expected << ", direct only " << direct);
  CHECK(std::abs(got / expected - 1) < 0.01);
  CHECK(expected > 1.9 * direct);  // the bounces matter
}

TEST_CASE("known answers: colour bleeds between a red and a green hemisphere as the two-patch equations say",
          "[pathtrace][known]") {
  // Inside a sphere every point's form factor to a patch of the wall is the
  // patch's area over the sphere's (dF = dA / 4 pi R^2), so with a lamp at
  // the centre each hemisphere has one radiance per channel, exactly:
  //   L_i = rho_i (E_d / pi + (L_1 + L_2) / 2),  E_d = pi Le (r / R)^2,
  // two patches of form factor 1/2 (the small lamp hides r^2 / R^2 of the
  // view, which is left out: 0.25 % of the bounced light).
  const double Le = 400, r = 0.05;
  const double red[3] = {0.8, 0.2, 0.2}, green[3] = {0.2, 0.8, 0.2};
  const std::string yaml = "version: 1\nprims:\n  /Looks: {type: Scope}\n  /Looks/Red: " + lambert(0.8, 0.2, 0.2) +
                           "\n  /Looks/Green: " + lambert(0.2, 0.8, 0.2) + "\n  /Top: {type: Mesh, asset: " +
                           fineHemisphereObj(true) + ", material: /Looks/Red}\n  /Bottom: {type: Mesh, asset: " +
                           fineHemisphereObj(false) +
                           ", material: /Looks/Green}\n"
                           "  /Lamp: {type: SphereLight, inputs:radius: 0.05, inputs:intensity: 400}\n"
                           "  /Down: {type: Camera, projection: orthographic, horizontalAperture: 10, translate: [0, 0, -0.2], "
                           "clippingRange: [0.01, 10]}\n"
                           "  /Up: {type: Camera, projection: orthographic, horizontalAperture: 10, translate: [0, 0, 0.2], "
                           "rotateXYZ: [180, 0, 0], clippingRange: [0.01, 10]}\n";
  const RenderList list = renderListOf(yaml);
  PathTraceSettings settings;
  settings.samples = 128;
  settings.maxBounces = 64;
  const PathTracedFrame bottom = trace(list, 16, 16, settings, 1, 0);
  const PathTracedFrame top = trace(list, 16, 16, settings, 2, 1);
  const double direct = Le * r * r;  // E_d / pi
  for (int c = 0; c < 3; ++c) {
    // L1 (1 - rho1/2) - L2 rho1/2 = rho1 d; -L1 rho2/2 + L2 (1 - rho2/2) = rho2 d.
    const double a = 1 - red[c] / 2, b = -red[c] / 2, e = -green[c] / 2, g = 1 - green[c] / 2;
    const double det = a * g - b * e;
    const double wantTop = (red[c] * direct * g - b * green[c] * direct) / det;
    const double wantBottom = (a * green[c] * direct - e * red[c] * direct) / det;
    double gotTop = 0, gotBottom = 0;
    for (size_t p = 0; p < top.instance.size(); ++p) {
      REQUIRE(top.instance[p] == 1u);
      REQUIRE(bottom.instance[p] == 2u);
      gotTop += top.radiance[3 * p + size_t(c)] / double(top.instance.size());
      gotBottom += bottom.radiance[3 * p + size_t(c)] / double(bottom.instance.size());
    }
    INFO("channel " << c << ": top (red) " << gotTop << " vs " << wantTop << ", bottom (green) " << gotBottom << " vs "
                    << wantBottom);
    CHECK(std::abs(gotTop / wantTop - 1) < 0.01);
    CHECK(std::abs(gotBottom / wantBottom - 1) < 0.01);
  }
  // The bleeding itself: the red half's green is well above its own
  // direct green (rho 0.2 d), lifted by the green half.
  const double ownGreen = 0.2 * direct;
  double topGreen = 0;
  for (size_t p = 0; p < top.instance.size(); ++p) topGreen += top.radiance[3 * p + 1] / double(top.instance.size());
  CHECK(topGreen > 1.5 * ownGreen);
}
