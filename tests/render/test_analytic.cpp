// Analytic render checks: values the formulas predict, measured on real
// OSMesa output.
#include "render_fixtures.h"

#include <cmath>
#include <numbers>
#include <set>

#include "run/scene_setup.h"
#include "render/camera_math.h"

using namespace sdg;

namespace {
// The renderer's colour pipeline for one linear radiance value.
int expectedSrgb8(double radiance, double exposureScale) {
  double mapped = 1.0 - std::exp(-radiance * exposureScale);
  double srgb = mapped <= 0.0031308 ? mapped * 12.92 : 1.055 * std::pow(mapped, 1.0 / 2.4) - 0.055;
  return int(std::lround(srgb * 255.0));
}

// A camera 10 units above the origin looking straight down (-Z).
const char* kTopCamera = R"(
  /Cam: {type: Camera, translate: [0, 0, 10], focalLength: 24, clippingRange: [0.1, 100]}
)";

// Uniform light from a dome and an orthographic camera 4 units wide looking
// down -Z: a card's texture shows flat, as stored.
const std::string kFlatLitTopView = R"(  /Sky: {type: DomeLight, inputs:intensity: 1000}
  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 40, translate: [0, 0, 10], clippingRange: [0.1, 100]}
)";

// A 100 x 100 render of a shadow scene and its red channel at a pixel: the
// scenes' cameras see 10 units across, 10 pixels per unit.
struct ShadowShot {
  test::RenderedScene r;
  int red(int x, int y) const { return int(r.frame.rgba[(size_t(y) * 100 + size_t(x)) * 4]); }
};
ShadowShot renderShadowScene(const std::string& yaml) {
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 100;
  return {test::renderYaml(yaml, settings)};
}

// Red minus blue at a pixel: positive on split.png's red half.
int redness(const FramePasses& f, int x, int y) {
  size_t i = (size_t(y) * size_t(f.width) + size_t(x)) * 4;
  return int(f.rgba[i]) - int(f.rgba[i + 2]);
}
}  // namespace

TEST_CASE("render: a plane lit head-on by a distant light has the shading formula's value", "[render][analytic]") {
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 64;
  auto r = test::renderYaml(std::string(R"(
version: 1
prims:
  /Looks: {type: Scope}
  /Looks/Grey: {type: Material, inputs:diffuse_color_constant: [0.5, 0.5, 0.5], inputs:reflection_roughness_constant: 1.0}
  /Floor: {type: Plane, width: 100, length: 100, material: /Looks/Grey}
  /Sun: {type: DistantLight, inputs:intensity: 1000}
)") + kTopCamera, settings);
  // Light and view both along the normal: n.l = n.v = n.h = v.h = 1.
  // Lambert: albedo / pi; GGX with alpha = 1: D = 1/pi, G = 1, F = 0.04.
  const double irradiance = 1000.0;
  const double brdf = 0.5 / std::numbers::pi + (1.0 / std::numbers::pi) * 0.04 / 4.0;
  const int expected = expectedSrgb8(brdf * irradiance, settings.exposureScale);
  const size_t centre = size_t(32 * 64 + 32) * 4;
  for (int c = 0; c < 3; ++c) CHECK(std::abs(int(r.frame.rgba[centre + size_t(c)]) - expected) <= 2);
  CHECK(r.frame.rgba[centre + 3] == 255);
}

TEST_CASE("render: a sphere's silhouette covers its analytic area within 1%", "[render][analytic]") {
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 256;
  // Orthographic: 10 units across (aperture in tenths of a unit), radius 3.
  auto r = test::renderYaml(R"(
version: 1
prims:
  /Ball: {type: Sphere, radius: 3}
  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 100, translate: [0, 0, 10], clippingRange: [0.1, 100]}
)",
                            settings);
  size_t covered = 0;
  for (uint32_t id : r.frame.instanceIds) covered += id != 0;
  const double pixelArea = (10.0 / 256) * (10.0 / 256);
  const double analytic = std::numbers::pi * 9.0;
  CHECK(std::fabs(covered * pixelArea - analytic) / analytic < 0.01);
}

TEST_CASE("render: distance to the image plane of a plane at a known distance", "[render][analytic]") {
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 64;
  auto r = test::renderYaml(std::string(R"(
version: 1
stage: {metersPerUnit: 0.01}
prims:
  /Floor: {type: Plane, width: 100, length: 100, translate: [0, 0, 2.5]}
)") + kTopCamera, settings);
  // 7.5 units in front of the camera; 0.01 m per unit.
  for (size_t i = 0; i < r.frame.pixelCount(); ++i) REQUIRE(std::fabs(r.frame.distanceToImagePlane[i] - 0.075f) < 1e-4);
  // Distance to the camera grows toward the corners: 0.075 / cos(angle).
  CHECK(r.frame.distanceToCamera[0] > r.frame.distanceToImagePlane[0]);
}

TEST_CASE("render: instance ids are exact on a known layout", "[render][analytic]") {
  RenderSettings settings = defaultRenderSettings();
  settings.width = 100;
  settings.height = 100;
  // Orthographic view of 10 x 10 units; two unit-size squares and background.
  auto r = test::renderYaml(R"(
version: 1
prims:
  /Left: {type: Cube, size: 2, translate: [-2.5, 0, 0]}
  /Right: {type: Cube, size: 2, translate: [2.5, 0, 0]}
  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 100, translate: [0, 0, 10], clippingRange: [0.1, 100]}
)",
                            settings);
  auto at = [&](int x, int y) { return r.frame.instanceIds[size_t(y) * 100 + size_t(x)]; };
  CHECK(at(25, 50) == 1);   // centre of /Left (x = -2.5)
  CHECK(at(75, 50) == 2);   // centre of /Right
  CHECK(at(50, 50) == 0);   // the gap
  CHECK(at(5, 5) == 0);     // corner
  // Each cube covers exactly 20 x 20 pixels (2 units at 10 px per unit).
  size_t left = 0, right = 0;
  for (uint32_t id : r.frame.instanceIds) {
    left += id == 1;
    right += id == 2;
  }
  CHECK(left == 400);
  CHECK(right == 400);
  CHECK(r.frame.distanceToImagePlane[0] == std::numeric_limits<float>::infinity());
  CHECK(r.frame.normals[size_t(50 * 100 + 25) * 4 + 2] == Approx(1.0f));  // world +Z facing the camera
}

TEST_CASE("render: a world point lands on the pixel the intrinsics predict", "[render][analytic]") {
  RenderSettings settings = defaultRenderSettings();
  settings.width = 160;
  settings.height = 120;
  auto r = test::renderYaml(R"(
version: 1
prims:
  /Dot: {type: Sphere, radius: 0.15, translate: [0.7, 0.4, 1.0]}
  /Cam: {type: Camera, focalLength: 18, horizontalApertureOffset: 1.5, translate: [0.2, -0.3, 6], rotateXYZ: [5, -3, 10], clippingRange: [0.1, 100]}
)",
                            settings);
  double sx = 0, sy = 0;
  size_t n = 0;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x)
      if (r.frame.instanceIds[size_t(y) * size_t(settings.width) + size_t(x)] == 1) {
        sx += x + 0.5;
        sy += y + 0.5;
        ++n;
      }
  REQUIRE(n > 10);
  Vec3d predicted = projectToPixel(r.list.cameras[0], settings.width, settings.height, Vec3d(0.7, 0.4, 1.0));
  CHECK(std::fabs(sx / double(n) - predicted.x()) < 0.5);
  CHECK(std::fabs(sy / double(n) - predicted.y()) < 0.5);
}

TEST_CASE("render: texture_rotate of 90 degrees rotates a texture", "[render][analytic]") {
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 64;
  auto render = [&](float rotate) {
    return test::renderYaml(R"(
version: 1
prims:
  /Looks: {type: Scope}
  /Looks/Split: {type: Material, inputs:diffuse_texture: images/split.png, inputs:texture_rotate: )" +
                                std::to_string(rotate) + R"(}
  /Card: {type: Plane, width: 4, length: 4, material: /Looks/Split}
)" + kFlatLitTopView,
                            settings);
  };
  // split.png: left half red, right half blue; the plane's uv runs 0..1.
  auto plain = render(0.0f);
  auto rotated = render(90.0f);
  // Unrotated: the colour changes from left to right, not from top to bottom.
  CHECK(redness(plain.frame, 16, 32) * redness(plain.frame, 48, 32) < 0);
  CHECK(redness(plain.frame, 32, 16) * redness(plain.frame, 32, 48) > 0);
  // Rotated 90 degrees: the split runs the other way.
  CHECK(redness(rotated.frame, 32, 16) * redness(rotated.frame, 32, 48) < 0);
  CHECK(redness(rotated.frame, 16, 32) * redness(rotated.frame, 48, 32) > 0);
}

TEST_CASE("render: project_uvw maps a texture from world coordinates, the mesh's uvs otherwise", "[render][analytic]") {
  // Two cards side by side in one frame (the renderer switches programs
  // between them): the left one samples split.png once over its uvs, the
  // right one repeats it every world unit.
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 64;
  auto r = test::renderYaml(R"(
version: 1
prims:
  /Looks: {type: Scope}
  /Looks/Uv: {type: Material, inputs:diffuse_texture: images/split.png}
  /Looks/World: {type: Material, inputs:diffuse_texture: images/split.png, inputs:project_uvw: true}
  /Left: {type: Plane, width: 2, length: 4, translate: [-1, 0, 0], material: /Looks/Uv}
  /Right: {type: Plane, width: 2, length: 4, translate: [1, 0, 0], material: /Looks/World}
)" + kFlatLitTopView,
                            settings);
  auto signChanges = [&](int from, int to) {
    int changes = 0;
    for (int x = from + 1; x < to; ++x) changes += (redness(r.frame, x, 32) > 0) != (redness(r.frame, x - 1, 32) > 0);
    return changes;
  };
  CHECK(signChanges(1, 31) == 1);  // red to blue once, mid-card
  CHECK(signChanges(33, 63) == 3);  // x = 0.5, 1 and 1.5: split, repeat, split
}

TEST_CASE("render: a distant light's shadow falls where the light direction puts it", "[render][analytic][shadows]") {
  auto shot = renderShadowScene(R"(
version: 1
prims:
  /Looks: {type: Scope}
  /Looks/Grey: {type: Material, inputs:diffuse_color_constant: [0.5, 0.5, 0.5], inputs:reflection_roughness_constant: 1.0}
  /Floor: {type: Plane, width: 20, length: 20, material: /Looks/Grey}
  /Block: {type: Cube, size: 2, translate: [0, 0, 3], material: /Looks/Grey}
  /Sun: {type: DistantLight, inputs:intensity: 1000, rotateY: 30}
  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 100, translate: [0, 0, 10], clippingRange: [0.1, 100]}
)");
  // The sun shines down -Z tilted 30 degrees toward -X: the block (x -1..1,
  // z 2..4) shadows the floor for x in [-3.31, -0.15]; 10 px per unit.
  CHECK(shot.red(25, 50) <= 2);   // floor at x = -2.5: in shadow, no ambient light
  CHECK(shot.red(85, 50) > 100);  // floor at x = +3.5: lit
  CHECK(shot.red(5, 50) > 100);   // floor at x = -4.5: beyond the shadow
}

TEST_CASE("render: a sphere light casts a shadow too", "[render][analytic][shadows]") {
  auto shot = renderShadowScene(R"(
version: 1
prims:
  /Floor: {type: Plane, width: 20, length: 20}
  /Block: {type: Cube, size: 1, translate: [1.5, 0, 2.5]}
  /Lamp: {type: SphereLight, inputs:intensity: 100000, inputs:radius: 0.1, translate: [3, 0, 5]}
  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 100, translate: [0, 0, 10], clippingRange: [0.1, 100]}
)");
  // The line from the lamp through the block's centre meets the floor at the
  // origin; x = 6 is as far from the lamp and unshadowed.
  CHECK(shot.red(50, 50) <= 2);
  CHECK(shot.red(95, 50) > 20);
}

TEST_CASE("render: a flat card above the floor casts its shadow, the floor under everything casts none",
          "[render][analytic][shadows]") {
  // Shadow maps leave out flat items with nothing behind them (the floor
  // here) but must keep a card with the floor behind it.
  auto shot = renderShadowScene(R"(
version: 1
prims:
  /Floor: {type: Plane, width: 20, length: 20}
  /Card: {type: Plane, width: 2, length: 2, translate: [0, 0, 2]}
  /Sun: {type: DistantLight, inputs:intensity: 1000, rotateY: 30}
  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 100, translate: [0, 0, 10], clippingRange: [0.1, 100]}
)");
  // The sun shines down -Z tilted 30 degrees toward -X: the card (x -1..1 at
  // z = 2) shadows the floor for x in [-2.15, -0.15]; 10 px per unit.
  CHECK(shot.red(30, 50) <= 2);   // floor at x = -2: in the card's shadow
  CHECK(shot.red(75, 50) > 100);  // floor at x = +2.5: lit
  CHECK(shot.red(5, 50) > 100);   // floor at x = -4.5: lit, no acne from the missing floor
  CHECK(shot.red(55, 50) > 100);  // the card itself at x = +0.5: lit
}

TEST_CASE("render: a dome light's lat-long texture shows behind the scene, its pole up", "[render][analytic][dome]") {
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 64;
  // sky.png: top half blue, bottom half green. On a Z-up stage the map's
  // pole is +Z; the camera looks along +Y with +Z up, so the top of the
  // picture is the dome's upper hemisphere.
  auto r = test::renderYaml(R"(
version: 1
prims:
  /Sky: {type: DomeLight, inputs:intensity: 2000, inputs:texture:file: images/sky.png}
  /Cam: {type: Camera, focalLength: 10, rotateXYZ: [90, 0, 0]}
)",
                            settings);
  auto px = [&](int x, int y, int c) { return int(r.frame.rgba[(size_t(y) * 64 + size_t(x)) * 4 + size_t(c)]); };
  CHECK(px(32, 5, 2) > px(32, 5, 1) + 50);    // top: blue
  CHECK(px(32, 58, 1) > px(32, 58, 2) + 50);  // bottom: green
  CHECK(r.frame.instanceIds[0] == 0);
  CHECK(r.frame.distanceToCamera[0] == std::numeric_limits<float>::infinity());
}

TEST_CASE("render: colour does not depend on the passes read back or on the pipelined path",
          "[render][passes]") {
  // Shared meshes, a textured and an untextured material, file and prim
  // materials: every batching path, drawn twice with different passes.
  const std::string yaml = std::string(R"(
version: 1
prims:
  /Looks: {type: Scope}
  /Looks/Wood: {type: Material, inputs:diffuse_texture: textures/wood.png, inputs:project_uvw: true}
  /Looks/Red: {type: Material, inputs:diffuse_color_constant: [0.8, 0.1, 0.1]}
  /Floor: {type: Plane, width: 20, length: 20, material: /Looks/Wood}
  /A: {type: Cube, size: 1, translate: [-1, 0, 0.5], material: /Looks/Red}
  /B: {type: Cube, size: 1, translate: [1, 0, 0.5]}
  /C: {type: Cube, size: 1, translate: [0, 1.5, 0.5], material: /Looks/Wood}
  /Crate: {type: Mesh, asset: props/crate.obj, translate: [0, -1.5, 0]}
  /Sun: {type: DistantLight, inputs:intensity: 2000, rotateXYZ: [30, 20, 0]}
  /Lamp: {type: SphereLight, inputs:intensity: 50000, translate: [2, 2, 4]}
)") + kTopCamera;
  RenderSettings settings = defaultRenderSettings();
  settings.width = settings.height = 96;
  auto full = test::renderYaml(yaml, settings);
  static const AssetResolver assets({SDG_SOURCE_DIR "/scenes", SDG_SOURCE_DIR "/tests/data"});
  Renderer renderer(test::sharedContext(), assets, settings);
  FramePasses colourOnly;
  renderer.render(full.list, 0, colourOnly, PassSelection::colourOnly());
  CHECK(colourOnly.rgba == full.frame.rgba);
  // Buffers a run does not read back are never allocated.
  CHECK((colourOnly.normals.empty() && colourOnly.distanceToCamera.empty() && colourOnly.distanceToImagePlane.empty() &&
         colourOnly.instanceIds.empty()));
  // The pipelined path gives the same bytes as the synchronous one.
  FramePasses pipelined;
  renderer.queue(full.list, 0, PassSelection{}, 0);
  renderer.collect(0, pipelined);
  CHECK(pipelined.rgba == full.frame.rgba);
  CHECK(pipelined.instanceIds == full.frame.instanceIds);
  // Every item keeps its own instance id through the batching.
  std::set<uint32_t> ids(full.frame.instanceIds.begin(), full.frame.instanceIds.end());
  for (const RenderItem& item : full.list.items) CHECK(ids.count(item.instanceId) == 1);
}
