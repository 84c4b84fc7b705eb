// The calibrated lens models (render/lens_model.h): values worked out by hand
// from each model's formula, and project/unproject round trips across the
// image, including a fisheye wider than 180 degrees.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "render/lens_model.h"

using namespace sdg;
using Eigen::Vector2d;

namespace {

constexpr double kPi = std::numbers::pi;
// Round trips go through Newton's method, stopped at 1e-12 in normalized
// coordinates: a millionth of a pixel leaves room for the focal lengths.
constexpr double kPixelTolerance = 1e-6;

// The USD camera-frame direction at `theta` from the axis, turned `phi` from
// +x toward the image's down (OpenCV's +y).
Vec3d usdDirection(double theta, double phi) {
  return Vec3d(std::sin(theta) * std::cos(phi), -std::sin(theta) * std::sin(phi), -std::cos(theta));
}

// A model of `kind` calibrated at width x height with centre (cx, cy) and
// coefficients k (each model's own: see LensModel::k).
LensModel lensWith(LensModelKind kind, Vector2d size, Vector2d centre, std::array<double, 6> k) {
  LensModel l;
  l.kind = kind;
  l.calibratedSize = size;
  l.cx = centre.x(), l.cy = centre.y();
  l.k = k;
  return l;
}

LensModel strongPinhole() {
  LensModel l = lensWith(LensModelKind::OpenCvPinhole, {160, 120}, {81, 58}, {-0.28, 0.07, 0.0, 0.01, 0.0, 0.0});
  l.fx = 100, l.fy = 110;
  l.p1 = 0.002, l.p2 = -0.003;
  l.s = {0.001, 0.0, -0.001, 0.0};
  return l;
}

LensModel wideFisheye() {
  LensModel l = lensWith(LensModelKind::OpenCvFisheye, {160, 120}, {79.5, 59.5}, {0.02, -0.004, 0.0005, 0, 0, 0});
  l.fx = 36, l.fy = 36;
  return l;
}

LensModel ftheta() {
  LensModel l = lensWith(LensModelKind::FTheta, {320, 240}, {160, 120}, {0.0, 0.0095, 1e-6, 0, 0, 0});
  l.maxFovDegrees = 200;
  return l;
}

LensModel kannalaBrandt() {
  LensModel l = lensWith(LensModelKind::KannalaBrandtK3, {160, 120}, {80, 60}, {40, -1.0, 0.1, 0, 0, 0});
  l.maxFovDegrees = 190;
  return l;
}

void requireNear(const Vector2d& a, const Vector2d& b, double tolerance) {
  INFO("(" << a.x() << ", " << a.y() << ") vs (" << b.x() << ", " << b.y() << ")");
  REQUIRE((a - b).norm() < tolerance);
}

// Every pixel centre with a ray goes there and back; returns how many had one.
int roundTripPixels(const LensModel& lens, int width, int height) {
  int withRay = 0;
  for (int y = 0; y < height; y += 3)
    for (int x = 0; x < width; x += 3) {
      const Vector2d pixel(x, y);
      const std::optional<Vec3d> ray = lensUnproject(lens, pixel, width, height);
      if (!ray) continue;
      ++withRay;
      REQUIRE(std::fabs(ray->norm() - 1.0) < 1e-12);
      const std::optional<Vector2d> back = lensProject(lens, *ray, width, height);
      REQUIRE(back);
      requireNear(*back, pixel, kPixelTolerance);
    }
  return withRay;
}

}  // namespace

TEST_CASE("lens model tokens are the omni:lensdistortion:model values", "[lens]") {
  for (const char* token : {"opencvPinhole", "opencvFisheye", "ftheta", "kannalaBrandtK3"})
    REQUIRE(lensModelToken(*lensModelFromToken(token)) == token);
  REQUIRE(lensModelFromToken("") == LensModelKind::Pinhole);
  REQUIRE_FALSE(lensModelFromToken("fisheyePolynomial"));
}

TEST_CASE("opencvPinhole projects as OpenCV's formula, worked by hand", "[lens]") {
  LensModel l;
  l.kind = LensModelKind::OpenCvPinhole;
  l.calibratedSize = Vector2d(160, 120);
  l.fx = 100, l.fy = 120, l.cx = 80, l.cy = 60;
  l.k[0] = 0.1;
  l.p1 = 0.01;
  // OpenCV frame (0.1, 0.2, 1): r2 = 0.05, radial 1.005,
  // xd = 0.1005 + 2 p1 x y = 0.1009, yd = 0.201 + p1 (r2 + 2 y^2) = 0.2023.
  const std::optional<Vector2d> p = lensProject(l, Vec3d(0.1, -0.2, -1.0), 160, 120);
  REQUIRE(p);
  requireNear(*p, Vector2d(90.09, 84.276), 1e-9);
  // Behind the camera: not imaged.
  REQUIRE_FALSE(lensProject(l, Vec3d(0.1, 0.0, 1.0), 160, 120));
}

TEST_CASE("a render of another size than imageSize scales the intrinsics edge to edge", "[lens]") {
  LensModel l;
  l.kind = LensModelKind::OpenCvPinhole;
  l.calibratedSize = Vector2d(320, 240);
  l.fx = l.fy = 200, l.cx = 159.5, l.cy = 119.5;
  // The axis lands on the centre of the calibrated image, 159.5: at half the
  // size, on 79.5; a point at the calibrated image's left edge (-0.5) stays
  // on the edge (-0.5).
  requireNear(*lensProject(l, Vec3d(0, 0, -1), 160, 120), Vector2d(79.5, 59.5), 1e-12);
  requireNear(*lensProject(l, Vec3d(-160.0 / 200.0, 0, -1), 160, 120), Vector2d(-0.5, 59.5), 1e-12);
  requireNear(*lensProject(l, Vec3d(-160.0 / 200.0, 0, -1), 640, 480), Vector2d(-0.5, 239.5), 1e-12);
}

TEST_CASE("opencvFisheye images beyond 90 degrees (a 190 degree lens)", "[lens]") {
  LensModel l;
  l.kind = LensModelKind::OpenCvFisheye;
  l.calibratedSize = Vector2d(160, 120);
  l.fx = l.fy = 50, l.cx = 80, l.cy = 60;
  // Equidistant (k = 0): 95 degrees from the axis lands 50 * 1.6581 px out.
  const double theta = 95.0 * kPi / 180.0;
  const std::optional<Vector2d> p = lensProject(l, usdDirection(theta, 0.0), 160, 120);
  REQUIRE(p);
  requireNear(*p, Vector2d(80 + 50 * theta, 60), 1e-9);
  const std::optional<Vec3d> ray = lensUnproject(l, *p, 160, 120);
  REQUIRE(ray);
  REQUIRE(ray->z() > 0.0);  // behind the image plane: the lens sees backwards
  REQUIRE((*ray - usdDirection(theta, 0.0)).norm() < 1e-9);
  REQUIRE(l.maxTheta() == Approx(kPi));
}

TEST_CASE("ftheta maps the pixel radius to the angle, kannalaBrandtK3 the angle to the radius", "[lens]") {
  LensModel f;
  f.kind = LensModelKind::FTheta;
  f.calibratedSize = Vector2d(160, 120);
  f.cx = 80, f.cy = 60;
  f.k = {0.0, 0.01, 0, 0, 0, 0};  // 0.01 rad per pixel
  f.maxFovDegrees = 200;
  // 100 px right of the centre: 1 rad.
  REQUIRE((*lensUnproject(f, Vector2d(180, 60), 160, 120) - usdDirection(1.0, 0.0)).norm() < 1e-12);
  requireNear(*lensProject(f, usdDirection(1.0, 0.5 * kPi), 160, 120), Vector2d(80, 160), 1e-9);
  // Beyond maxFov / 2 = 100 degrees: no ray, no pixel.
  REQUIRE_FALSE(lensUnproject(f, Vector2d(80 + 180, 60), 160, 120));
  REQUIRE_FALSE(lensProject(f, usdDirection(101.0 * kPi / 180.0, 0.0), 160, 120));

  LensModel kb;
  kb.kind = LensModelKind::KannalaBrandtK3;
  kb.calibratedSize = Vector2d(160, 120);
  kb.cx = 80, kb.cy = 60;
  kb.k = {100, 0, 0, 0, 0, 0};
  kb.maxFovDegrees = 180;
  requireNear(*lensProject(kb, usdDirection(0.5, kPi), 160, 120), Vector2d(30, 60), 1e-9);
}

TEST_CASE("every model's rays project back onto their pixels", "[lens]") {
  for (const LensModel& lens : {strongPinhole(), wideFisheye(), ftheta(), kannalaBrandt()}) {
    INFO("model " << lensModelToken(lens.kind));
    // At the calibrated size and at another (the intrinsics scaled).
    REQUIRE(roundTripPixels(lens, 160, 120) > 100);
    REQUIRE(roundTripPixels(lens, 96, 64) > 50);
  }
}

TEST_CASE("directions inside the field of view come back from their pixels", "[lens]") {
  for (const LensModel& lens : {strongPinhole(), wideFisheye(), ftheta(), kannalaBrandt()}) {
    INFO("model " << lensModelToken(lens.kind));
    const double maxTheta = lens.kind == LensModelKind::OpenCvPinhole ? 0.5 : 0.98 * lens.maxTheta();
    for (double theta = 0.0; theta <= maxTheta; theta += maxTheta / 7)
      for (double phi = 0.0; phi < 2 * kPi; phi += kPi / 5) {
        const Vec3d d = usdDirection(theta, phi);
        const std::optional<Vector2d> pixel = lensProject(lens, d, 160, 120);
        REQUIRE(pixel);
        const std::optional<Vec3d> back = lensUnproject(lens, *pixel, 160, 120);
        REQUIRE(back);
        INFO("theta " << theta << " phi " << phi);
        REQUIRE((*back - d).norm() < 1e-8);
      }
  }
}

TEST_CASE("a fisheye whose polynomial turns back stops imaging where it does", "[lens]") {
  LensModel l = wideFisheye();
  l.k = {-0.2, 0, 0, 0, 0, 0};  // theta_d = t - 0.2 t^3 peaks at t = 1.29
  REQUIRE(l.maxTheta() == Approx(std::sqrt(1.0 / 0.6)).margin(2e-3));
  REQUIRE_FALSE(lensProject(l, usdDirection(1.4, 0.0), 160, 120));
  // A pixel beyond the largest theta_d has no ray.
  REQUIRE_FALSE(lensUnproject(l, Vector2d(79.5 + 36 * 0.9, 59.5), 160, 120));
}
