// The rasterizer's plan for a calibrated lens (render/lens_views.h), without
// GL: each pixel of the lens's image takes the pixel of a pinhole view that
// its own ray passes through (checked with camera_math.h's projection, the
// one the rasterizer draws with), the views are at least as dense as the
// image at its centre, and the resampling copies every pass unblended.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "render/camera_math.h"
#include "render/lens_views.h"

using namespace sdg;
using Eigen::Vector2d;

namespace {

constexpr int kWidth = 160, kHeight = 120;

RenderCamera fisheyeCamera() {
  RenderCamera c;
  c.path = "/Cam";
  c.nearClip = 0.1f;
  c.farClip = 100.0f;
  LensModel& l = c.lens;
  l.kind = LensModelKind::OpenCvFisheye;
  l.calibratedSize = Vector2d(kWidth, kHeight);
  l.fx = l.fy = 32, l.cx = 79.5, l.cy = 59.5;
  l.k = {0.01, -0.002, 0, 0, 0, 0};
  l.prepare();
  return c;
}

RenderCamera pinholeCamera() {
  RenderCamera c = fisheyeCamera();
  LensModel& l = c.lens;
  l = LensModel{};
  l.kind = LensModelKind::OpenCvPinhole;
  l.calibratedSize = Vector2d(kWidth, kHeight);
  l.fx = 110, l.fy = 105, l.cx = 81, l.cy = 58.5;
  l.k = {-0.3, 0.09, -0.01, 0.02, 0, 0};
  l.p1 = 0.004, l.p2 = -0.003;
  l.prepare();
  return c;
}

}  // namespace

TEST_CASE("lens views: every pixel samples the view pixel its ray goes through", "[lens]") {
  for (const RenderCamera& camera : {fisheyeCamera(), pinholeCamera()}) {
    INFO("model " << lensModelToken(camera.lens.kind));
    const LensViewPlan plan = planLensViews(camera, kWidth, kHeight);
    // The fisheye needs the cube (all 6 faces: the image's corners, past its
    // 190 degree circle, see nearly straight back), the pinhole one frustum
    // in 2 x 2 tiles.
    if (camera.lens.kind == LensModelKind::OpenCvFisheye) CHECK(plan.viewTemplates.size() == 6);
    else CHECK(plan.viewTemplates.size() == 4);
    int imaged = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const size_t i = size_t(y) * kWidth + size_t(x);
        const std::optional<Vec3d> ray = lensUnproject(camera.lens, Vector2d(x, y), kWidth, kHeight);
        REQUIRE(ray.has_value() == (plan.view[i] >= 0));
        if (!ray) continue;
        ++imaged;
        const RenderCamera view = lensView(plan, camera, size_t(plan.view[i]));
        const Vec3d p = projectToPixel(view, kWidth, kHeight, *ray * 5.0);
        REQUIRE(p.z() > 0);
        const uint32_t expected = uint32_t(std::floor(p.y())) * kWidth + uint32_t(std::floor(p.x()));
        INFO("pixel " << x << ", " << y << " lands at " << p.x() << ", " << p.y());
        REQUIRE(plan.sourcePixel[i] == expected);
        // The camera's depth from the view's: the point at distance 5.
        REQUIRE(p.z() * plan.planeScale[i] == Approx(5.0 * -ray->z()).margin(1e-5));
      }
    CHECK(imaged > kWidth * kHeight / 2);
  }
}

TEST_CASE("lens views: resampling copies each pass from its view, never blending", "[lens]") {
  const RenderCamera camera = fisheyeCamera();
  const LensViewPlan plan = planLensViews(camera, kWidth, kHeight);
  std::vector<FramePasses> views(plan.viewTemplates.size());
  const PassSelection all;
  for (size_t v = 0; v < views.size(); ++v) {
    views[v].resize(kWidth, kHeight, all);
    for (size_t s = 0; s < views[v].pixelCount(); ++s) {
      views[v].instanceIds[s] = uint32_t(v * 100000 + s);
      views[v].distanceToCamera[s] = float(s);
      views[v].distanceToImagePlane[s] = 2.0f;
      views[v].rgba[4 * s] = uint8_t(v);
    }
  }
  FramePasses out;
  resampleLensViews(plan, views, all, out);
  for (size_t i = 0; i < out.pixelCount(); ++i) {
    if (plan.view[i] < 0) {
      REQUIRE(out.instanceIds[i] == 0);
      REQUIRE(std::isinf(out.distanceToCamera[i]));
      REQUIRE(out.rgba[4 * i + 3] == 255);
      continue;
    }
    REQUIRE(out.instanceIds[i] == uint32_t(plan.view[i]) * 100000 + plan.sourcePixel[i]);
    REQUIRE(out.distanceToCamera[i] == float(plan.sourcePixel[i]));
    REQUIRE(out.distanceToImagePlane[i] == 2.0f * plan.planeScale[i]);
    REQUIRE(out.rgba[4 * i] == uint8_t(plan.view[i]));
  }
}
