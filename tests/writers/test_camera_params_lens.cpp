// camera_params for a camera with a calibrated lens (writers/annotators.h):
// the model in cameraModel, Isaac's fisheye keys where Isaac writes them,
// and the whole calibration under cameraLensDistortion, as authored.
#include <catch2/catch.hpp>

#include "writers/annotators.h"

using namespace sdg;

TEST_CASE("camera_params names a calibrated lens and its coefficients", "[lens][writers]") {
  RenderCamera pinhole;
  const nlohmann::ordered_json ideal = cameraParams(pinhole, 160, 120, 1.0);
  CHECK(ideal["cameraModel"] == "pinhole");
  CHECK_FALSE(ideal.contains("cameraLensDistortion"));
  CHECK(ideal["cameraFisheyeLensP"].empty());

  RenderCamera opencv;
  LensModel& l = opencv.lens;
  l.kind = LensModelKind::OpenCvPinhole;
  l.calibratedSize = Eigen::Vector2d(640, 480);
  l.fx = 500, l.fy = 510, l.cx = 319.5, l.cy = 241;
  l.k = {-0.2f, 0.05f, 0, 0.01f, 0, 0};  // float attributes, as the render list holds them
  l.p1 = 0.001f, l.p2 = -0.002f;
  l.s = {0.0003f, 0, 0, 0};
  const nlohmann::ordered_json j = cameraParams(opencv, 160, 120, 1.0);
  CHECK(j["cameraModel"] == "opencvPinhole");
  CHECK(j["cameraFisheyeLensP"] == nlohmann::ordered_json::array({0.001, -0.002}));
  CHECK(j["cameraFisheyeLensS"] == nlohmann::ordered_json::array({0.0003, 0.0, 0.0, 0.0}));
  const nlohmann::ordered_json& d = j["cameraLensDistortion"];
  CHECK(d["model"] == "opencvPinhole");
  CHECK(d["fy"] == 510.0);
  CHECK(d["cy"] == 241.0);
  CHECK(d["imageSize"] == nlohmann::ordered_json::array({640, 480}));
  CHECK(d["k1"] == -0.2);  // the float's shortest decimal form
  CHECK(d["k4"] == 0.01);
  CHECK(d["s1"] == 0.0003);

  RenderCamera ftheta;
  LensModel& f = ftheta.lens;
  f.kind = LensModelKind::FTheta;
  f.calibratedSize = Eigen::Vector2d(1936, 1216);
  f.cx = 970.9424f, f.cy = 600.3748f;
  f.k = {0, 0.00245f, 0, 0, 1e-12f, 0};
  f.maxFovDegrees = 200;
  const nlohmann::ordered_json t = cameraParams(ftheta, 160, 120, 1.0);
  CHECK(t["cameraModel"] == "ftheta");
  CHECK(t["cameraFisheyeNominalWidth"] == 1936);
  CHECK(t["cameraFisheyeNominalHeight"] == 1216);
  CHECK(t["cameraFisheyeOpticalCentre"] == nlohmann::ordered_json::array({970.9424, 600.3748}));
  CHECK(t["cameraFisheyeMaxFOV"] == 200.0);
  CHECK(t["cameraFisheyePolynomial"] == nlohmann::ordered_json::array({0.0, 0.00245, 0.0, 0.0, 1e-12}));
  CHECK(t["cameraFisheyeLensP"].empty());
  CHECK(t["cameraLensDistortion"]["k4"] == 1e-12);
}
