// Calibrated lenses on cameras (omni:lensdistortion:*): the same names from
// YAML and USD, a schema applied without its model token, located errors
// for bad values, the render list's LensModel, and export-usd writing the
// lens back with its schema.
#include <catch2/catch.hpp>

#include <cmath>

#include "render/render_list.h"
#include "scene_io/scene_fixtures.h"
#include "scene_io/usd_export.h"
#include "scene_io/usd_fixtures.h"
#include "usd/usda_writer.h"

using namespace sdg;
using sdg::test::errorsOf;
using sdg::test::loadText;

namespace {

const char* kFisheyeYaml = R"(version: 1
prims:
  /World: {}
  /World/Cam:
    type: Camera
    omni:lensdistortion:model: opencvFisheye
    omni:lensdistortion:opencvFisheye:imageSize: [640, 480]
    omni:lensdistortion:opencvFisheye:fx: 200
    omni:lensdistortion:opencvFisheye:fy: 201
    omni:lensdistortion:opencvFisheye:cx: 319.5
    omni:lensdistortion:opencvFisheye:cy: 239.5
    omni:lensdistortion:opencvFisheye:k2: -0.01
)";

}  // namespace

TEST_CASE("lens: YAML attributes reach the render list's camera", "[lens][scene_io]") {
  Scene scene = loadText(kFisheyeYaml);
  const RenderList list = buildRenderList(scene.stage);
  REQUIRE(list.cameras.size() == 1);
  const LensModel& lens = list.cameras[0].lens;
  CHECK(lens.kind == LensModelKind::OpenCvFisheye);
  CHECK(lens.calibratedSize == Eigen::Vector2d(640, 480));
  CHECK(lens.fx == 200.0);
  CHECK(lens.fy == 201.0);
  CHECK(lens.cx == 319.5);
  CHECK(lens.k[1] == Approx(-0.01));
  // Prepared: theta_d = theta (1 - 0.01 theta^4) increases up to theta^4 = 20.
  CHECK(lens.thetaLimit == Approx(std::pow(20.0, 0.25)).margin(2e-3));
  CHECK(anyCalibratedLens(list));
}

TEST_CASE("lens: bad values are located errors at the attribute", "[lens][scene_io]") {
  struct Case {
    const char* lines;
    const char* message;
  } cases[] = {
      {"    omni:lensdistortion:model: fisheyePolynomial\n",
       "t.yaml:6:32: error: /Cam.omni:lensdistortion:model: expected one of"},
      {"    omni:lensdistortion:model: opencvPinhole\n    omni:lensdistortion:opencvPinhole:fx: 0\n",
       "t.yaml:7:43: error: /Cam.omni:lensdistortion:opencvPinhole:fx: expected a focal length greater than 0, found 0"},
      {"    omni:lensdistortion:model: opencvFisheye\n    omni:lensdistortion:opencvFisheye:fy: -3\n",
       "/Cam.omni:lensdistortion:opencvFisheye:fy: expected a focal length greater than 0, found -3"},
      {"    omni:lensdistortion:model: opencvPinhole\n    omni:lensdistortion:opencvPinhole:imageSize: [0, 10]\n",
       "/Cam.omni:lensdistortion:opencvPinhole:imageSize: expected a width and height greater than 0, found 0 x 10"},
      {"    omni:lensdistortion:model: ftheta\n    omni:lensdistortion:ftheta:k1: 0\n",
       "/Cam.omni:lensdistortion:ftheta:k1: expected radians per pixel greater than 0, found 0"},
      {"    omni:lensdistortion:model: kannalaBrandtK3\n",
       "/Cam.omni:lensdistortion:kannalaBrandtK3:k0: expected pixels per radian greater than 0, found 0"},
      {"    omni:lensdistortion:model: ftheta\n    projection: orthographic\n",
       "a calibrated lens needs projection = perspective"},
      {"    omni:lensdistortion:model: opencvPinhole\n    omni:lensdistortion:opencvPinhole:k1: .nan\n",
       "/Cam.omni:lensdistortion:opencvPinhole:k1"},
      // Another model's values are not used, so not checked.
      {"    omni:lensdistortion:opencvPinhole:fx: 0\n", ""},
  };
  for (const Case& c : cases) {
    const std::string yaml = std::string("version: 1\nprims:\n  /Cam:\n    type: Camera\n    clippingRange: [0.1, 10]\n") + c.lines;
    CAPTURE(yaml);
    const std::string errors = errorsOf(yaml);
    if (std::string(c.message).empty()) CHECK(errors.empty());
    else CHECK_THAT(errors, Catch::Contains(c.message));
  }
}

TEST_CASE("lens: a USD camera's applied schema gives the model, radTanThinPrism is a counted loss", "[lens][usd_import]") {
  test::ImportedStage in;
  test::importText(R"(#usda 1.0
def Xform "W"
{
    def Camera "Fisheye" (prepend apiSchemas = ["OmniLensDistortionOpenCvFisheyeAPI"])
    {
        float omni:lensdistortion:opencvFisheye:fx = 300
        float omni:lensdistortion:opencvFisheye:fy = 300
        int2 omni:lensdistortion:opencvFisheye:imageSize = (1280, 720)
        float omni:lensdistortion:opencvFisheye:k1 = 0.05
    }
    def Camera "Ftheta" (prepend apiSchemas = ["OmniLensDistortionFthetaAPI"])
    {
        token omni:lensdistortion:model = "ftheta"
        float2 omni:lensdistortion:ftheta:opticalCenter = (960, 600)
    }
    def Camera "Prism" (prepend apiSchemas = ["OmniLensDistortionRadTanThinPrismAPI"])
    {
        token omni:lensdistortion:model = "radTanThinPrism"
    }
}
)", in);
  REQUIRE_FALSE(in.diag.hasErrors());
  const Prim& fisheye = *in.stage.find("/W/Fisheye");
  CHECK(fisheye.getString("omni:lensdistortion:model") == "opencvFisheye");
  CHECK(fisheye.getFloat("omni:lensdistortion:opencvFisheye:k1") == 0.05f);
  CHECK(fisheye.value("omni:lensdistortion:opencvFisheye:imageSize")->get<Vec2i>() == Vec2i(1280, 720));
  const Prim& ftheta = *in.stage.find("/W/Ftheta");
  CHECK(ftheta.getString("omni:lensdistortion:model") == "ftheta");
  CHECK(ftheta.value("omni:lensdistortion:ftheta:opticalCenter")->get<Vec2f>() == Vec2f(960, 600));
  CHECK(in.stage.find("/W/Prism")->getString("omni:lensdistortion:model").empty());
  bool prismCounted = false, readCounted = false;
  for (const DroppedWarning& w : in.report.losses.warnings()) {
    prismCounted = prismCounted || w.info.what == "OmniLensDistortionRadTanThinPrismAPI";
    readCounted = readCounted || w.info.what.find("OpenCvFisheye") != std::string::npos ||
                  w.info.what.find("Ftheta") != std::string::npos;
  }
  CHECK(prismCounted);
  CHECK_FALSE(readCounted);
}

TEST_CASE("lens: export-usd writes the attributes and applies the model's schema", "[lens][usd_export]") {
  Scene scene = loadText(kFisheyeYaml);
  UsdExportOptions options;
  options.catalog = &test::builtinCatalog();
  const std::string text = usd::writeUsdaLayer(exportUsdLayer(scene, AssetResolver{}, options));
  CHECK_THAT(text, Catch::Contains("OmniLensDistortionOpenCvFisheyeAPI"));
  CHECK_THAT(text, Catch::Contains("omni:lensdistortion:opencvFisheye:fx = 200"));
  CHECK_THAT(text, Catch::Contains("int2 omni:lensdistortion:opencvFisheye:imageSize = (640, 480)"));
  // Read back: the same lens.
  test::ImportedStage in;
  test::importText(text, in);
  REQUIRE_FALSE(in.diag.hasErrors());
  const Prim& cam = *in.stage.find("/World/Cam");
  CHECK(cam.getString("omni:lensdistortion:model") == "opencvFisheye");
  CHECK(cam.getFloat("omni:lensdistortion:opencvFisheye:fy") == 201.0f);
  CHECK(cam.getFloat("omni:lensdistortion:opencvFisheye:k2") == -0.01f);
}
