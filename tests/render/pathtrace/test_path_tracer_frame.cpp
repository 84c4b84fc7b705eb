// The path tracer's frame: byte-identical whatever the thread count, label
// planes that line up with the rasterizer's camera, the dome seen in its
// documented orientation, cut-outs and normal maps as the rasterizer reads
// them, and the tone curve.
#include "pt_test_scenes.h"

#include <array>
#include <cstring>
#include <functional>
#include <optional>

#include "render/camera_math.h"
#include "render/latlong.h"
#include "render/test_images.h"
#include "writers/png_encoder.h"

using namespace sdg;
using sdg::test::writePng;
using sdg::test::writeRgbe;
using namespace sdg::pttest;
namespace fs = std::filesystem;

namespace {


const char* kRoom = R"(version: 1
prims:
  /Looks: {type: Scope}
  /Looks/White: {type: Material, inputs:diffuse_color_constant: [0.73, 0.73, 0.73], inputs:reflection_roughness_constant: 1.0}
  /Looks/Metal: {type: Material, inputs:diffuse_color_constant: [0.9, 0.7, 0.3], inputs:reflection_roughness_constant: 0.2, inputs:metallic_constant: 1}
  /Floor: {type: Plane, width: 2, length: 2, material: /Looks/White}
  /Back: {type: Plane, axis: Y, width: 2, length: 2, translate: [0, 1, 1], material: /Looks/White}
  /Left: {type: Plane, axis: X, width: 2, length: 2, translate: [-1, 0, 1], primvars:displayColor: [0.6, 0.1, 0.1]}
  /Box: {type: Cube, size: 0.6, translate: [0.3, 0.2, 0.3], rotateZ: 20, material: /Looks/Metal}
  /Ball: {type: Sphere, radius: 0.25, translate: [-0.4, -0.2, 0.25]}
  /Lamp: {type: RectLight, inputs:width: 0.5, inputs:height: 0.5, inputs:intensity: 800, translate: [0, 0, 1.9]}
  /Sun: {type: DistantLight, inputs:angle: 2, inputs:intensity: 2, rotateXYZ: [30, 10, 0]}
  /Sky: {type: DomeLight, inputs:intensity: 0.3}
  /Camera: {type: Camera, focalLength: 24, clippingRange: [0.1, 100], translate: [0, -3.2, 1], rotateX: 90}
)";

// Where a ray first meets an axis-aligned box's surface after tMin = 0:
// its entry, or its exit when it starts inside.
std::optional<double> hitBox(const Vec3d& o, const Vec3d& d, const Vec3d& lo, const Vec3d& hi) {
  double t0 = -std::numeric_limits<double>::infinity(), t1 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
    t0 = std::max(t0, std::min(a, b));
    t1 = std::min(t1, std::max(a, b));
  }
  if (t0 > t1 || t1 <= 0) return std::nullopt;
  return t0 > 0 ? t0 : t1;
}

}  // namespace

TEST_CASE("path tracer: the radiance is byte-identical on 1 and 3 threads, and the seed changes it", "[pathtrace]") {
  const RenderList list = renderListOf(kRoom);
  PathTraceSettings settings;
  settings.samples = 8;
  settings.maxBounces = 8;
  settings.threads = 1;
  const PathTracedFrame one = trace(list, 40, 24, settings, 5);
  settings.threads = 3;
  const PathTracedFrame three = trace(list, 40, 24, settings, 5);
  REQUIRE(one.radiance.size() == three.radiance.size());
  CHECK(std::memcmp(one.radiance.data(), three.radiance.data(), one.radiance.size() * sizeof(float)) == 0);
  CHECK(std::memcmp(one.albedo.data(), three.albedo.data(), one.albedo.size() * sizeof(float)) == 0);
  CHECK(std::memcmp(one.normal.data(), three.normal.data(), one.normal.size() * sizeof(float)) == 0);
  CHECK(std::memcmp(one.depth.data(), three.depth.data(), one.depth.size() * sizeof(float)) == 0);
  CHECK(one.instance == three.instance);
  const PathTracedFrame other = trace(list, 40, 24, settings, 6);
  CHECK(std::memcmp(one.radiance.data(), other.radiance.data(), one.radiance.size() * sizeof(float)) != 0);
  CHECK(one.instance == other.instance);  // labels do not depend on the seed
}

TEST_CASE("path tracer: each pixel's instance and depth are those of the ray through its centre, as the rasterizer projects",
          "[pathtrace]") {
  // Axis-aligned boxes (the cubes, scaled) at several depths, one of them
  // nearer than the near clipping plane; a wide image with an aperture
  // offset, in perspective and orthographic.
  struct Box {
    Vec3d centre, half;
  };
  const std::vector<Box> boxes = {{{0, 0, 0}, {3, 3, 0.05}},
                                  {{0.4, 0.3, 0.5}, {0.3, 0.2, 0.5}},
                                  {{-0.6, -0.2, 0.3}, {0.2, 0.4, 0.3}},
                                  {{0.1, -0.9, 0.2}, {0.15, 0.15, 0.2}},
                                  {{0.25, -0.05, 4.2}, {0.05, 0.05, 0.25}}};  // z 3.95 .. 4.45: cut by the near plane
  std::string prims;
  for (size_t i = 0; i < boxes.size(); ++i) {
    const Box& b = boxes[i];
    char line[256];
    std::snprintf(line, sizeof line, "  /Box%zu: {type: Cube, size: 2, translate: [%g, %g, %g], scale: [%g, %g, %g]}\n", i,
                  b.centre.x(), b.centre.y(), b.centre.z(), b.half.x(), b.half.y(), b.half.z());
    prims += line;
  }
  for (const bool orthographic : {false, true}) {
    INFO((orthographic ? "orthographic" : "perspective"));
    const std::string camera =
        orthographic ? "  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 40, horizontalApertureOffset: 3, "
                       "translate: [0.2, -0.1, 5], rotateXYZ: [8, -5, 0], clippingRange: [0.7, 100]}\n"
                     : "  /Cam: {type: Camera, focalLength: 30, horizontalApertureOffset: 2, verticalApertureOffset: -1, "
                       "translate: [0.2, -0.1, 5], rotateXYZ: [8, -5, 0], clippingRange: [0.7, 100]}\n";
    const RenderList list = renderListOf("version: 1\nprims:\n" + prims + camera);
    REQUIRE(list.items.size() == boxes.size());
    const int w = 48, h = 30;
    PathTraceSettings settings;
    settings.samples = 1;
    settings.maxBounces = 0;
    const PathTracedFrame f = trace(list, w, h, settings);
    // The rasterizer's projection, inverted through its own matrices: the
    // ray through each pixel's centre, from the near plane.
    const RenderCamera& cam = list.cameras[0];
    const Matrix4d worldFromClip = (projectionMatrix(cam, w, h) * viewMatrix(cam)).inverse();
    const Vec3d eye = cam.worldFromCamera.block<3, 1>(0, 3);
    int compared = 0, mismatched = 0, insideClipped = 0;
    double worstDepth = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double nx = 2.0 * (x + 0.5) / w - 1.0, ny = 1.0 - 2.0 * (y + 0.5) / h;
        const Eigen::Vector4d a = worldFromClip * Eigen::Vector4d(nx, ny, -1, 1);
        const Eigen::Vector4d b = worldFromClip * Eigen::Vector4d(nx, ny, 1, 1);
        const Vec3d origin = a.head<3>() / a.w(), direction = (b.head<3>() / b.w() - origin).normalized();
        // The point lands back on the pixel centre (the inversion is right).
        const Vec3d back = projectToPixel(cam, w, h, origin + direction);
        REQUIRE(std::abs(back.x() - (x + 0.5)) < 1e-6);
        REQUIRE(std::abs(back.y() - (y + 0.5)) < 1e-6);
        // The first box along the ray, with every box grown and shrunk by
        // 1e-5: a ray that close to an edge or a tie is left out.
        auto first = [&](double grow) {
          std::pair<uint32_t, double> best{0u, std::numeric_limits<double>::infinity()};
          for (size_t i = 0; i < boxes.size(); ++i) {
            const Vec3d g = Vec3d::Constant(grow);
            const auto t = hitBox(origin, direction, boxes[i].centre - boxes[i].half - g, boxes[i].centre + boxes[i].half + g);
            if (t && *t < best.second) best = {list.items[i].instanceId, *t};
          }
          return best;
        };
        const auto [id, t] = first(0.0);
        if (first(1e-5).first != id || first(-1e-5).first != id) continue;
        ++compared;
        const size_t p = size_t(y * w + x);
        if (f.instance[p] != id) {
          ++mismatched;
          continue;
        }
        if (id == 0) {
          CHECK(std::isinf(f.depth[p]));
          continue;
        }
        const double depth = (origin + t * direction - eye).norm();
        worstDepth = std::max(worstDepth, std::abs(f.depth[p] - depth));
        // The clipped box seen from inside: its far face, past the near plane.
        if (id == list.items[4].instanceId) ++insideClipped;
      }
    INFO("compared " << compared << ", mismatched " << mismatched << ", worst depth error " << worstDepth);
    CHECK(compared > w * h * 9 / 10);
    CHECK(mismatched == 0);
    CHECK(worstDepth < 1e-4);
    // The box the near plane cuts is seen through its open near side.
    CHECK(insideClipped > 0);
  }
}

TEST_CASE("path tracer: the camera sees the dome map in OpenEXR's lat-long orientation, its pole on the stage's up axis",
          "[pathtrace]") {
  const fs::path dir = scratchFolder("dome");
  // The rasterizer's test map: sectors by longitude (u = 0.25 along the
  // dome's +X, 0.5 along +Z, 0.75 along -X) and a yellow cap at the pole.
  test::writeSectorSky(dir / "sectors.hdr");
  // Z-up: the dome's +Y turns to +Z, so +X stays +X, +Z becomes -Y, -Z +Y.
  const RenderList list = renderListOf(
      "version: 1\nprims:\n  /Sky: {type: DomeLight, inputs:intensity: 250, inputs:texture:file: " +
      (dir / "sectors.hdr").string() + R"(}
  /PlusX: {type: Camera, focalLength: 50, rotateXYZ: [90, 0, -90]}
  /MinusY: {type: Camera, focalLength: 50, rotateXYZ: [90, 0, 180]}
  /MinusX: {type: Camera, focalLength: 50, rotateXYZ: [90, 0, 90]}
  /PlusY: {type: Camera, focalLength: 50, rotateXYZ: [90, 0, 0]}
  /Up: {type: Camera, focalLength: 50, rotateXYZ: [180, 0, 0]}
)");
  REQUIRE(list.cameras.size() == 5);
  const std::array<Vec3f, 5> expected = {Vec3f(1000, 0, 0), Vec3f(0, 1000, 0), Vec3f(0, 0, 1000),
                                         Vec3f(1000, 1000, 1000), Vec3f(1000, 1000, 0)};
  PathTraceSettings settings;
  settings.samples = 4;
  settings.maxBounces = 8;
  PathTracer tracer(testAssets(), settings);
  for (size_t c = 0; c < expected.size(); ++c) {
    INFO("camera " << list.cameras[c].path);
    PathTracedFrame f;
    tracer.render(list, c, 16, 16, 1, f);
    const size_t centre = 8 * 16 + 8;
    for (int k = 0; k < 3; ++k) CHECK(f.radiance[3 * centre + size_t(k)] == Approx(expected[c][k]).margin(1e-3));
    CHECK(f.instance[centre] == 0u);
    CHECK(std::isinf(f.depth[centre]));
  }
}

TEST_CASE("path tracer: an opacity cut-out lets camera rays and shadow rays through where it is clear", "[pathtrace]") {
  const fs::path dir = scratchFolder("opacity");
  writePng(dir / "left_clear.png", 8, 8, [](int x, int) {
    const uint8_t v = x < 4 ? 0 : 255;
    return std::array<uint8_t, 4>{v, v, v, 255};
  });
  // The rasterizer's cut-out scene, lit by a sun straight down: the card
  // shades the floor only under its solid half.
  const std::string yaml =
      "version: 1\nprims:\n  /Looks: {type: Scope}\n"
      "  /Looks/Red: {type: Material, inputs:diffuse_color_constant: [0.8, 0.05, 0.05]}\n"
      "  /Looks/Card: {type: Material, inputs:diffuse_color_constant: [0.05, 0.05, 0.8], inputs:enable_opacity: true, "
      "inputs:enable_opacity_texture: true, inputs:opacity_threshold: 0.5, inputs:opacity_texture: " +
      (dir / "left_clear.png").string() + R"(}
  /Floor: {type: Plane, width: 20, length: 20, material: /Looks/Red}
  /Card: {type: Plane, width: 4, length: 4, translate: [0, 0, 1], material: /Looks/Card}
  /Sun: {type: DistantLight, inputs:angle: 0, inputs:intensity: 1000}
  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 40, translate: [0, 0, 10], clippingRange: [0.1, 100]}
  /Wide: {type: Camera, projection: orthographic, horizontalAperture: 100, translate: [0, 0, 10], clippingRange: [0.1, 100]}
)";
  const RenderList list = renderListOf(yaml);
  const uint32_t floorId = list.items[0].instanceId, cardId = list.items[1].instanceId;
  PathTraceSettings settings;
  settings.samples = 4;
  settings.maxBounces = 8;
  const PathTracedFrame top = trace(list, 32, 32, settings);
  // The card covers pixels 8..23; its left half (x < 16) is cut out.
  CHECK(top.instance[size_t(16 * 32 + 11)] == floorId);
  CHECK(top.instance[size_t(16 * 32 + 20)] == cardId);
  // The red floor through the hole (its 4 % coat adds a white highlight
  // of the sun overhead).
  CHECK(top.radiance[3 * size_t(16 * 32 + 11)] > 3 * top.radiance[3 * size_t(16 * 32 + 11) + 2]);
  CHECK(top.radiance[3 * size_t(16 * 32 + 20) + 2] > top.radiance[3 * size_t(16 * 32 + 20)]);       // the blue card
  // A sun 45 degrees off (toward +Y) shifts the card's shadow one unit
  // along +Y: beyond the card (y 2 .. 3) the floor is lit behind the
  // clear half (x < 0) and shaded behind the solid one, in a wider view.
  const std::string slanted = std::string(yaml).replace(yaml.find("inputs:intensity: 1000}"), 23,
                                                        "inputs:intensity: 1000, rotateXYZ: [45, 0, 0]}");
  const PathTracedFrame wide = trace(renderListOf(slanted), 32, 32, settings, 1, 1);
  // 10 units across, 0.3125 a pixel: y = 2.5 is row 8, x = -1 column 12, x = +1 column 19.
  const size_t lit = size_t(8 * 32 + 12), shaded = size_t(8 * 32 + 19);
  CHECK(wide.instance[lit] == floorId);
  CHECK(wide.instance[shaded] == floorId);
  INFO("lit " << wide.radiance[3 * lit] << ", shaded " << wide.radiance[3 * shaded]);
  CHECK(wide.radiance[3 * lit] > 50);
  CHECK(wide.radiance[3 * shaded] < 0.02 * wide.radiance[3 * lit]);
}

TEST_CASE("path tracer: a normal map tilts the shading toward the image's top, as in the rasterizer", "[pathtrace]") {
  const fs::path dir = scratchFolder("normal");
  writePng(dir / "top_red.png", 8, 8, [](int, int y) {
    return y < 4 ? std::array<uint8_t, 4>{255, 0, 0, 255} : std::array<uint8_t, 4>{0, 0, 255, 255};
  });
  // Every texel's normal tilted 45 degrees toward the image's top (+Y).
  writePng(dir / "tilt_up.png", 8, 8, [](int, int) { return std::array<uint8_t, 4>{128, 218, 218, 255}; });
  const std::string d = dir.string() + "/";
  const std::string camera =
      "  /Cam: {type: Camera, projection: orthographic, horizontalAperture: 40, translate: [0, 0, 10], clippingRange: [0.1, 100]}\n";
  PathTraceSettings settings;
  settings.samples = 4;
  settings.maxBounces = 8;
  // Where the image's top lies on screen, from the albedo plane.
  const PathTracedFrame look =
      trace(renderListOf("version: 1\nprims:\n  /Looks: {type: Scope}\n  /Looks/M: {type: Material, inputs:diffuse_texture: " +
                         d + "top_red.png}\n  /Card: {type: Plane, width: 4, length: 4, material: /Looks/M}\n" + camera),
            32, 32, settings);
  auto redAt = [&](int x, int y) { return look.albedo[3 * size_t(y * 32 + x)] > look.albedo[3 * size_t(y * 32 + x) + 2]; };
  const int topSign = redAt(16, 4) ? 1 : -1;  // +1: the image's top at the screen's top (world +Y)
  CHECK(redAt(16, 28) == (topSign < 0));
  // A grazing sun from the image's top side, then from the other side.
  auto brightness = [&](bool mapped, int side) {
    const std::string normal = mapped ? ", inputs:normalmap_texture: " + d + "tilt_up.png" : "";
    const std::string yaml =
        "version: 1\nprims:\n  /Looks: {type: Scope}\n  /Looks/M: {type: Material, inputs:diffuse_color_constant: [0.8, 0.8, 0.8], "
        "inputs:reflection_roughness_constant: 1" + normal +
        "}\n  /Card: {type: Plane, width: 4, length: 4, material: /Looks/M}\n"
        "  /Sun: {type: DistantLight, inputs:angle: 0, inputs:intensity: 1500, rotateXYZ: [" +
        std::to_string(-60 * topSign * side) + ", 0, 0]}\n" + camera;
    return trace(renderListOf(yaml), 32, 32, settings).radiance[3 * size_t(16 * 32 + 16) + 1];
  };
  // Tilted 45 degrees toward a sun 60 degrees off the normal: cos 15 vs
  // cos 60, nearly twice as bright; away from it, below the horizon.
  CHECK(brightness(true, 1) > 1.5 * brightness(false, 1));
  CHECK(brightness(true, -1) < 0.5 * brightness(false, -1));
}

TEST_CASE("path tracer: toneMap is the rasterizer's curve, sRGB-encoded and rounded", "[pathtrace]") {
  PathTracedFrame f;
  f.width = 4;
  f.height = 1;
  // 0; the radiance that maps to 1 - exp(-2) (0.8647: sRGB 0.9380, code
  // 239.18) at the default exposure scale 0.002; a huge value; a negative one.
  f.radiance = {0, 0, 0, 1000, 1000, 1000, 1e30f, 1e30f, 1e30f, -5, -5, -5};
  std::vector<uint8_t> rgba(16);
  toneMap(f, 0.002f, rgba.data());
  CHECK(rgba[0] == 0);
  CHECK(rgba[3] == 255);
  CHECK(rgba[4] == 239);
  CHECK(rgba[8] == 255);
  CHECK(rgba[12] == 0);
}
