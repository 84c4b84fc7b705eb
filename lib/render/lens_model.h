#pragma once
// Calibrated lens models of NVIDIA's omni_lens_distortion schemas, as plain
// math (no GL): where a camera-space direction lands on the image and which
// ray leaves a pixel. The calibration replaces focalLength and the apertures
// for projection, as in Isaac Sim (docs/rendering.md, "Lens models").
//
// Frames: directions are in the USD camera frame (x right, y up, looking down
// -z). Pixels are OpenCV's: x right, y down, the centre of pixel (i, j) at
// (i, j), so a calibration's cx, cy and OpenCV's projectPoints agree with
// them directly (add 0.5 for the project's other pixel coordinates, whose
// centres are at .5).
#include <array>
#include <optional>
#include <string_view>

#include <Eigen/Core>

#include "stage/math_types.h"

namespace sdg {

enum class LensModelKind {
  Pinhole,          // no calibration: focalLength and the apertures (camera_math.h)
  OpenCvPinhole,    // "opencvPinhole": OpenCV's rational + tangential + thin-prism model
  OpenCvFisheye,    // "opencvFisheye": OpenCV's fisheye (equidistant + k1..k4 on theta)
  FTheta,           // "ftheta": NVIDIA's f-theta, angle = polynomial of the pixel radius
  KannalaBrandtK3,  // "kannalaBrandtK3": pixel radius = k0 t + k1 t^3 + k2 t^5 + k3 t^7
};

// The token of `omni:lensdistortion:model` for a kind ("" for Pinhole), and
// back (nullopt for a token no model here has).
std::string_view lensModelToken(LensModelKind kind);
std::optional<LensModelKind> lensModelFromToken(std::string_view token);

struct LensModel {
  LensModelKind kind = LensModelKind::Pinhole;
  // The size of the image the calibration was made for (pixels): imageSize,
  // or nominalWidth x nominalHeight. A render of another size scales the
  // model to it (pixel edges map to pixel edges).
  Eigen::Vector2d calibratedSize{0, 0};
  double fx = 0, fy = 0;  // OpenCV models (pixels)
  double cx = 0, cy = 0;  // OpenCV models' principal point; f-theta / K-B: opticalCenter
  // opencvPinhole k1..k6; opencvFisheye k1..k4 in k[0..3]; ftheta k0..k4;
  // kannalaBrandtK3 k0..k3.
  std::array<double, 6> k{};
  double p1 = 0, p2 = 0;        // opencvPinhole tangential
  std::array<double, 4> s{};    // opencvPinhole thin prism s1..s4
  double maxFovDegrees = 0;     // ftheta, kannalaBrandtK3: full field of view
  // maxTheta() once worked out (prepare()); 0 works it out on every use,
  // which takes a scan of the polynomial.
  double thetaLimit = 0;

  bool calibrated() const { return kind != LensModelKind::Pinhole; }
  // The largest angle from the optical axis (radians) the model images:
  // pi/2 for opencvPinhole, up to pi for opencvFisheye and
  // kannalaBrandtK3 (where the polynomial stops increasing; K-B also at
  // maxFov / 2), maxFov / 2 for ftheta.
  double maxTheta() const;
  // Fills thetaLimit once the parameters are set.
  void prepare() { thetaLimit = 0, thetaLimit = maxTheta(); }
};

// Where a direction lands on an image of width x height (OpenCV pixels);
// nullopt when the lens does not image it (behind an opencvPinhole, beyond
// maxTheta). The image may fall outside [0, width) x [0, height).
std::optional<Eigen::Vector2d> lensProject(const LensModel& lens, const Vec3d& direction, int width, int height);

// The unit direction whose ray reaches pixel position `pixel` (OpenCV
// pixels); nullopt where no ray does (outside the lens's image circle, or
// where the distortion cannot be inverted). Iterative where the model's
// inverse has no closed form; each iteration converges to 1e-12 in
// normalized coordinates or gives nullopt (docs/rendering.md).
std::optional<Vec3d> lensUnproject(const LensModel& lens, const Eigen::Vector2d& pixel, int width, int height);

}  // namespace sdg
