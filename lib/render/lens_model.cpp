#include "render/lens_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sdg {
namespace {

using Eigen::Vector2d;

constexpr double kPi = std::numbers::pi;
// Newton's iterations stop here (normalized coordinates or radians): far
// below a pixel at any focal length a calibration has.
constexpr double kTolerance = 1e-12;
constexpr int kMaxIterations = 100;

// Calibrated pixels <-> render pixels: pixel edges map to pixel edges, so a
// render of half the calibrated size sees the same field of view.
Vector2d scaleOf(const LensModel& lens, int width, int height) {
  const Vector2d size = lens.calibratedSize.x() > 0 && lens.calibratedSize.y() > 0 ? lens.calibratedSize
                                                                                   : Vector2d(width, height);
  return Vector2d(width / size.x(), height / size.y());
}
Vector2d toRender(const Vector2d& calibrated, const Vector2d& scale) {
  return ((calibrated.array() + 0.5) * scale.array() - 0.5).matrix();
}
Vector2d toCalibrated(const Vector2d& render, const Vector2d& scale) {
  return ((render.array() + 0.5) / scale.array() - 0.5).matrix();
}

// USD camera frame (y up, looking down -z) <-> OpenCV's (y down, looking down +z).
Vec3d toOpenCv(const Vec3d& d) { return Vec3d(d.x(), -d.y(), -d.z()); }
Vec3d fromOpenCv(const Vec3d& d) { return Vec3d(d.x(), -d.y(), -d.z()).normalized(); }

// The unit direction at angle theta from the axis toward (dx, dy) (OpenCV frame).
Vec3d directionAt(double theta, double dx, double dy) {
  const double r = std::hypot(dx, dy);
  if (r == 0.0) return fromOpenCv(Vec3d(0, 0, 1));
  const double s = std::sin(theta);
  return fromOpenCv(Vec3d(s * dx / r, s * dy / r, std::cos(theta)));
}

// Solves f(t) = target for t in [lo, hi] with f increasing there: Newton's
// steps kept inside a shrinking bracket (bisection when a step leaves it).
template <class F, class DF>
std::optional<double> solveIncreasing(F f, DF df, double target, double lo, double hi) {
  if (!std::isfinite(target) || target < f(lo) || target > f(hi)) return std::nullopt;
  double t = std::clamp(target, lo, hi);  // f is near identity for every model's normalized form
  for (int i = 0; i < kMaxIterations; ++i) {
    const double residual = f(t) - target;
    if (std::fabs(residual) <= kTolerance * std::max(1.0, std::fabs(target))) return t;
    (residual < 0 ? lo : hi) = t;
    if (hi - lo <= kTolerance) return t;
    const double slope = df(t);
    double next = slope > 0 ? t - residual / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    t = next;
  }
  return std::nullopt;
}

// opencvPinhole: normalized undistorted (x, y) -> distorted, as OpenCV's
// projectPoints (rational radial, tangential, thin prism).
Vector2d distortPinhole(const LensModel& l, const Vector2d& p) {
  const double x = p.x(), y = p.y();
  const double r2 = x * x + y * y, r4 = r2 * r2, r6 = r4 * r2;
  const double radial = (1 + l.k[0] * r2 + l.k[1] * r4 + l.k[2] * r6) / (1 + l.k[3] * r2 + l.k[4] * r4 + l.k[5] * r6);
  return Vector2d(x * radial + 2 * l.p1 * x * y + l.p2 * (r2 + 2 * x * x) + l.s[0] * r2 + l.s[1] * r4,
                  y * radial + l.p1 * (r2 + 2 * y * y) + 2 * l.p2 * x * y + l.s[2] * r2 + l.s[3] * r4);
}

Eigen::Matrix2d pinholeJacobian(const LensModel& l, const Vector2d& p) {
  constexpr double h = 1e-7;
  Eigen::Matrix2d j;
  j.col(0) = (distortPinhole(l, p + Vector2d(h, 0)) - distortPinhole(l, p - Vector2d(h, 0))) / (2 * h);
  j.col(1) = (distortPinhole(l, p + Vector2d(0, h)) - distortPinhole(l, p - Vector2d(0, h))) / (2 * h);
  return j;
}

// opencvFisheye: theta_d(theta) and its derivative.
double fisheyeThetaD(const LensModel& l, double t) {
  const double t2 = t * t;
  return t * (1 + t2 * (l.k[0] + t2 * (l.k[1] + t2 * (l.k[2] + t2 * l.k[3]))));
}
double fisheyeSlope(const LensModel& l, double t) {
  const double t2 = t * t;
  return 1 + t2 * (3 * l.k[0] + t2 * (5 * l.k[1] + t2 * (7 * l.k[2] + t2 * 9 * l.k[3])));
}

// ftheta: angle(r) = k0 + k1 r + k2 r^2 + k3 r^3 + k4 r^4, r in calibrated pixels.
double fthetaAngle(const LensModel& l, double r) {
  return l.k[0] + r * (l.k[1] + r * (l.k[2] + r * (l.k[3] + r * l.k[4])));
}
double fthetaSlope(const LensModel& l, double r) { return l.k[1] + r * (2 * l.k[2] + r * (3 * l.k[3] + r * 4 * l.k[4])); }

// kannalaBrandtK3: radius(theta) = k0 t + k1 t^3 + k2 t^5 + k3 t^7 (calibrated pixels).
double kbRadius(const LensModel& l, double t) {
  const double t2 = t * t;
  return t * (l.k[0] + t2 * (l.k[1] + t2 * (l.k[2] + t2 * l.k[3])));
}
double kbSlope(const LensModel& l, double t) {
  const double t2 = t * t;
  return l.k[0] + t2 * (3 * l.k[1] + t2 * (5 * l.k[2] + t2 * 7 * l.k[3]));
}

// The first angle in (0, limit] where `slope` stops being positive, or limit.
template <class DF>
double increasingUpTo(DF slope, double limit) {
  constexpr int kSteps = 2048;
  for (int i = 1; i <= kSteps; ++i) {
    const double t = limit * i / kSteps;
    if (!(slope(t) > 0)) return limit * (i - 1) / kSteps;
  }
  return limit;
}

// The f-theta pixel radius reaching `theta` (nullopt beyond the polynomial's
// increasing range): the bracket grows until it holds the angle.
std::optional<double> fthetaRadius(const LensModel& l, double theta) {
  auto f = [&](double r) { return fthetaAngle(l, r); };
  auto df = [&](double r) { return fthetaSlope(l, r); };
  if (theta <= f(0)) return 0.0;
  double hi = 1.0;
  while (f(hi) < theta) {
    if (!(df(hi) > 0) || hi > 1e7) return std::nullopt;
    hi *= 2;
  }
  return solveIncreasing(f, df, theta, 0.0, hi);
}

}  // namespace

std::string_view lensModelToken(LensModelKind kind) {
  switch (kind) {
    case LensModelKind::Pinhole: return "";
    case LensModelKind::OpenCvPinhole: return "opencvPinhole";
    case LensModelKind::OpenCvFisheye: return "opencvFisheye";
    case LensModelKind::FTheta: return "ftheta";
    case LensModelKind::KannalaBrandtK3: return "kannalaBrandtK3";
  }
  return "";
}

std::optional<LensModelKind> lensModelFromToken(std::string_view token) {
  for (LensModelKind k : {LensModelKind::Pinhole, LensModelKind::OpenCvPinhole, LensModelKind::OpenCvFisheye,
                          LensModelKind::FTheta, LensModelKind::KannalaBrandtK3})
    if (lensModelToken(k) == token) return k;
  return std::nullopt;
}

double LensModel::maxTheta() const {
  if (thetaLimit > 0) return thetaLimit;
  switch (kind) {
    case LensModelKind::Pinhole:
    case LensModelKind::OpenCvPinhole: return 0.5 * kPi;
    case LensModelKind::OpenCvFisheye: return increasingUpTo([&](double t) { return fisheyeSlope(*this, t); }, kPi);
    case LensModelKind::FTheta: return std::min(kPi, 0.5 * maxFovDegrees * kPi / 180.0);
    case LensModelKind::KannalaBrandtK3:
      return increasingUpTo([&](double t) { return kbSlope(*this, t); }, std::min(kPi, 0.5 * maxFovDegrees * kPi / 180.0));
  }
  return 0.0;
}

std::optional<Vector2d> lensProject(const LensModel& l, const Vec3d& direction, int width, int height) {
  const Vec3d d = toOpenCv(direction);
  const double r = std::hypot(d.x(), d.y());
  const double theta = std::atan2(r, d.z());
  if (!std::isfinite(theta) || direction.squaredNorm() == 0.0) return std::nullopt;
  // The unit vector toward the point in the image plane (any, on the axis).
  const Vector2d toward = r > 0 ? Vector2d(d.x() / r, d.y() / r) : Vector2d(1, 0);
  Vector2d calibrated(0, 0);
  switch (l.kind) {
    case LensModelKind::Pinhole: return std::nullopt;  // camera_math.h projects these
    case LensModelKind::OpenCvPinhole: {
      if (!(d.z() > 0)) return std::nullopt;
      const Vector2d p(d.x() / d.z(), d.y() / d.z());
      // Past the fold of a strong distortion the image turns back on itself:
      // such points are not imaged where the polynomial puts them.
      if (!(pinholeJacobian(l, p).determinant() > 0)) return std::nullopt;
      const Vector2d q = distortPinhole(l, p);
      calibrated = Vector2d(l.fx * q.x() + l.cx, l.fy * q.y() + l.cy);
      break;
    }
    case LensModelKind::OpenCvFisheye: {
      if (theta > l.maxTheta()) return std::nullopt;
      const double td = fisheyeThetaD(l, theta);
      calibrated = Vector2d(l.fx * td * toward.x() + l.cx, l.fy * td * toward.y() + l.cy);
      break;
    }
    case LensModelKind::FTheta: {
      if (theta > l.maxTheta()) return std::nullopt;
      const std::optional<double> radius = fthetaRadius(l, theta);
      if (!radius) return std::nullopt;
      calibrated = Vector2d(l.cx, l.cy) + *radius * toward;
      break;
    }
    case LensModelKind::KannalaBrandtK3: {
      if (theta > l.maxTheta()) return std::nullopt;
      calibrated = Vector2d(l.cx, l.cy) + kbRadius(l, theta) * toward;
      break;
    }
  }
  return toRender(calibrated, scaleOf(l, width, height));
}

std::optional<Vec3d> lensUnproject(const LensModel& l, const Vector2d& pixel, int width, int height) {
  const Vector2d c = toCalibrated(pixel, scaleOf(l, width, height));
  switch (l.kind) {
    case LensModelKind::Pinhole: return std::nullopt;
    case LensModelKind::OpenCvPinhole: {
      // Newton's method on distort(p) = q from p = q (the distortion is near
      // the identity at the centre); a fold or a non-converging pixel has no ray.
      const Vector2d q((c.x() - l.cx) / l.fx, (c.y() - l.cy) / l.fy);
      Vector2d p = q;
      for (int i = 0; i < kMaxIterations; ++i) {
        const Vector2d residual = distortPinhole(l, p) - q;
        const Eigen::Matrix2d j = pinholeJacobian(l, p);
        if (!(j.determinant() > 0)) return std::nullopt;
        if (residual.norm() <= kTolerance * std::max(1.0, q.norm())) return fromOpenCv(Vec3d(p.x(), p.y(), 1.0));
        p -= j.inverse() * residual;
        if (!p.allFinite()) return std::nullopt;
      }
      return std::nullopt;
    }
    case LensModelKind::OpenCvFisheye: {
      const Vector2d q((c.x() - l.cx) / l.fx, (c.y() - l.cy) / l.fy);
      const std::optional<double> theta =
          solveIncreasing([&](double t) { return fisheyeThetaD(l, t); }, [&](double t) { return fisheyeSlope(l, t); },
                          q.norm(), 0.0, l.maxTheta());
      if (!theta) return std::nullopt;
      return directionAt(*theta, q.x(), q.y());
    }
    case LensModelKind::FTheta: {
      const Vector2d q = c - Vector2d(l.cx, l.cy);
      const double r = q.norm();
      // The polynomial must be increasing from the centre to this radius.
      for (int i = 1; i <= 16; ++i)
        if (!(fthetaSlope(l, r * i / 16) > 0)) return std::nullopt;
      const double theta = std::max(0.0, fthetaAngle(l, r));
      if (theta > l.maxTheta()) return std::nullopt;
      return directionAt(theta, q.x(), q.y());
    }
    case LensModelKind::KannalaBrandtK3: {
      const Vector2d q = c - Vector2d(l.cx, l.cy);
      const std::optional<double> theta = solveIncreasing(
          [&](double t) { return kbRadius(l, t); }, [&](double t) { return kbSlope(l, t); }, q.norm(), 0.0, l.maxTheta());
      if (!theta) return std::nullopt;
      return directionAt(*theta, q.x(), q.y());
    }
  }
  return std::nullopt;
}

}  // namespace sdg
