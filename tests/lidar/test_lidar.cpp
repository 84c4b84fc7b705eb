// The LiDAR's pattern and casting against analytic answers: ranges in a
// closed box room by ray-box intersection, the rings' elevations and the
// columns' azimuths, the labels of a known object, the noise's sigma and
// the dropout fraction over 100,000 rays, and sweeps identical whatever
// the thread count. No rendering: the caster and the pattern alone.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <numeric>

#include "builtin_behaviors/builtin_behaviors.h"
#include "core/diagnostics.h"
#include "lidar/lidar_caster.h"
#include "render/render_list.h"
#include "scene_io/scene_loader.h"
#include "scene_io/usd_import.h"
#include "stage/lidar_pattern.h"
#include "writers/semantics.h"

using namespace sdg;

namespace {

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

const AssetResolver& assets() {
  static const AssetResolver resolver({SDG_SOURCE_DIR "/scenes"});
  return resolver;
}

Scene sceneOf(const std::string& prims) {
  return buildScene(sceneDocumentFromText("version: 1\nprims:\n" + prims, "t.yaml"), builtinRegistry().catalog());
}

// A room 10 x 6 x 4 (a cube scaled, seen from inside), centred at the origin.
const char* kRoom = "  /World: {type: Xform}\n  /World/Room: {type: Cube, size: 1, scale: [10, 6, 4]}\n";

LidarSweep sweepOf(const Scene& scene, const std::string& lidar, unsigned threads, uint64_t seed = 7) {
  const Prim& prim = *scene.stage.find(lidar);
  REQUIRE(lidarProblems(prim).empty());
  LidarCaster caster(assets(), threads);
  caster.setScene(buildRenderList(scene.stage));
  LidarSweep sweep;
  caster.cast(lidarPatternOf(prim), scene.stage.worldMatrix(prim), 1.0, seed, sweep);
  return sweep;
}

// The distance from `o` along unit `d` to the wall of the box [lo, hi] it
// leaves through (o inside).
double exitDistance(const Vec3d& o, const Vec3d& d, const Vec3d& lo, const Vec3d& hi) {
  double t = 1e300;
  for (int i = 0; i < 3; ++i)
    if (d[i] != 0.0) t = std::min(t, ((d[i] > 0 ? hi[i] : lo[i]) - o[i]) / d[i]);
  return t;
}

}  // namespace

TEST_CASE("lidar: presets and verticalFov give the rings' elevations, columns their azimuths and times", "[lidar]") {
  Scene scene = sceneOf(
      "  /A: {type: Lidar, preset: VLP-16, horizontalResolution: 1800, rotationRate: 10}\n"
      "  /B: {type: Lidar, channels: 5, verticalFov: [-20, 20], horizontalResolution: 4}\n"
      "  /C: {type: Lidar, pattern: solidState, channels: 3, verticalFov: [-10, 10], horizontalFov: 90, "
      "horizontalResolution: 5}\n");
  const LidarPattern a = lidarPatternOf(*scene.stage.find("/A"));
  REQUIRE(a.channels() == 16);
  for (uint32_t r = 0; r < 16; ++r) CHECK(a.elevations[r] == Approx(-15.0 + 2.0 * r));
  CHECK(a.azimuth(450) == Approx(90.0));
  CHECK(a.timeOffset(900) == Approx(0.05));
  const LidarPattern b = lidarPatternOf(*scene.stage.find("/B"));
  CHECK(b.elevations == std::vector<float>{-20, -10, 0, 10, 20});
  CHECK(b.direction(2, 1).isApprox(Vec3f(0, 1, 0), 1e-6f));  // elevation 0, azimuth 90: +y
  CHECK(b.direction(4, 0).z() == Approx(std::sin(20 / kDegrees)));
  const LidarPattern c = lidarPatternOf(*scene.stage.find("/C"));
  CHECK(c.azimuth(0) == Approx(45.0));
  CHECK(c.azimuth(2) == Approx(0.0));
  CHECK(c.azimuth(4) == Approx(-45.0));
  for (const LidarPreset& p : lidarPresets()) CHECK(!p.source.empty());
}

TEST_CASE("lidar: every ray in a closed box room returns the ray-box distance within 1 mm, in its ring", "[lidar]") {
  // Off-centre and turned, so that no wall is at a round distance.
  Scene scene = sceneOf(std::string(kRoom) +
                        "  /World/Lidar: {type: Lidar, channels: 32, verticalFov: [-40, 30], horizontalResolution: 360, "
                        "translate: [1.3, -0.7, 0.4], rotateXYZ: [0, 0, 27]}\n");
  const LidarSweep sweep = sweepOf(scene, "/World/Lidar", 2);
  REQUIRE(sweep.returns.size() == 32 * 360);
  const Vec3d origin(1.3, -0.7, 0.4), lo(-5, -3, -2), hi(5, 3, 2);
  const Matrix3d rotation = sweep.worldFromSensor.block<3, 3>(0, 0);
  double worst = 0;
  for (size_t i = 0; i < sweep.returns.size(); ++i) {
    const LidarReturn& r = sweep.returns[i];
    REQUIRE(r.hit());
    const uint32_t column = uint32_t(i / 32);
    const Vec3d local = sweep.pattern.direction(r.ring, column).cast<double>();
    const Vec3d d = (rotation * local).normalized();
    worst = std::max(worst, std::abs(double(r.range) - exitDistance(origin, d, lo, hi)));
    // The point lies on its ring's cone and at its column's azimuth.
    CHECK(std::asin(r.z / r.range) * kDegrees == Approx(sweep.pattern.elevations[r.ring]).margin(1e-3));
    const double azimuth = std::atan2(r.y, r.x) * kDegrees;
    CHECK(std::remainder(azimuth - r.azimuth, 360.0) == Approx(0.0).margin(1e-3));
  }
  INFO("largest range error " << worst << " m");
  CHECK(worst < 1e-3);
}

TEST_CASE("lidar: points on a labelled object carry its render id, and through it its class and instance", "[lidar]") {
  Scene scene = sceneOf(std::string(kRoom) +
                        "  /World/Box: {type: Cube, size: 1, translate: [3, 0, 0], semantics: {class: crate}}\n"
                        "  /World/Lidar: {type: Lidar, channels: 16, verticalFov: [-10, 10], horizontalResolution: 720}\n");
  const LidarSweep sweep = sweepOf(scene, "/World/Lidar", 1);
  const RenderList list = buildRenderList(scene.stage);
  const FrameSemantics semantics = computeSemantics(scene.stage, list, {"class"});
  uint32_t boxId = 0;
  for (const RenderItem& item : list.items)
    if (item.primPath == "/World/Box") boxId = item.instanceId;
  REQUIRE(boxId != 0);
  size_t onBox = 0;
  for (const LidarReturn& r : sweep.returns) {
    // The box's face at x = 2.5 spans |y| <= 0.5, |z| <= 0.5: well inside it, the box; well outside, the room.
    const double az = std::remainder(double(r.azimuth), 360.0);
    const bool inside = std::abs(az) < 8.0 && std::abs(sweep.pattern.elevations[r.ring]) < 9.0;
    const bool outside = std::abs(az) > 15.0;
    if (inside) CHECK(r.renderId == boxId);
    if (outside) CHECK(r.renderId != boxId);
    onBox += r.renderId == boxId;
  }
  CHECK(onBox > 100);
  const uint32_t entity = semantics.entityOfRenderId[boxId];
  REQUIRE(entity != 0);
  CHECK(semantics.entities[entity - 1].labels.at("class") == "crate");
  CHECK(semantics.entities[entity - 1].primPath == "/World/Box");
}

TEST_CASE("lidar: range noise has its sigma within 10 % and dropout its fraction, over 100,000 rays", "[lidar]") {
  const std::string sensor =
      "  /World/Lidar: {type: Lidar, channels: 128, verticalFov: [-30, 30], horizontalResolution: 800";
  Scene exact = sceneOf(std::string(kRoom) + sensor + "}\n");
  Scene noisy = sceneOf(std::string(kRoom) + sensor + ", rangeNoise: 0.02}\n");
  Scene dropped = sceneOf(std::string(kRoom) + sensor + ", dropout: 0.3}\n");
  const LidarSweep a = sweepOf(exact, "/World/Lidar", 2), b = sweepOf(noisy, "/World/Lidar", 2),
                   c = sweepOf(dropped, "/World/Lidar", 2);
  REQUIRE(a.returns.size() == 102400);
  double sum = 0, squares = 0;
  for (size_t i = 0; i < a.returns.size(); ++i) {
    const double e = double(b.returns[i].range) - double(a.returns[i].range);
    sum += e;
    squares += e * e;
  }
  const double n = double(a.returns.size()), mean = sum / n, sigma = std::sqrt(squares / n - mean * mean);
  INFO("mean " << mean << ", sigma " << sigma);
  CHECK(std::abs(sigma / 0.02 - 1.0) < 0.1);
  CHECK(std::abs(mean) < 0.001);
  const size_t lost = size_t(std::count_if(c.returns.begin(), c.returns.end(), [](const LidarReturn& r) { return !r.hit(); }));
  INFO("dropped " << lost << " of " << c.returns.size());
  CHECK(std::abs(double(lost) / n - 0.3) < 0.01);
  // Another seed draws other noise; the same seed the same.
  CHECK(sweepOf(noisy, "/World/Lidar", 1).returns[5].range == b.returns[5].range);
  CHECK(sweepOf(noisy, "/World/Lidar", 1, 8).returns[5].range != b.returns[5].range);
}

TEST_CASE("lidar: a sweep is the same bytes on 1 and 3 threads", "[lidar]") {
  Scene scene = sceneOf(std::string(kRoom) +
                        "  /World/Box: {type: Sphere, radius: 0.7, translate: [2, 1, 0]}\n"
                        "  /World/Lidar: {type: Lidar, preset: HDL-32E, horizontalResolution: 1000, rangeNoise: 0.01, "
                        "dropout: 0.1}\n");
  const LidarSweep one = sweepOf(scene, "/World/Lidar", 1), three = sweepOf(scene, "/World/Lidar", 3);
  REQUIRE(one.returns.size() == three.returns.size());
  CHECK(std::memcmp(one.returns.data(), three.returns.data(), one.returns.size() * sizeof(LidarReturn)) == 0);
}

TEST_CASE("lidar: hostile attributes are located errors naming the attribute", "[lidar]") {
  std::string message;
  try {
    sceneOf("  /A: {type: Lidar, channels: 0}\n"
            "  /B: {type: Lidar, range: [5, 2]}\n"
            "  /C: {type: Lidar, channels: 2, elevations: [1, 2, 3], dropout: 1.5}\n"
            "  /D: {type: Lidar, preset: OS1-64, channels: 64}\n"
            "  /E: {type: Lidar, rangeNoise: -1}\n");
  } catch (const SceneError& e) {
    message = e.what();
  }
  INFO(message);
  for (const char* expected :
       {"t.yaml:3:", "/A.channels: expected 1 to 4096 beams, found 0", "t.yaml:4:", "/B.range: expected [min, max]",
        "/C.elevations: expected one elevation per channel (2), found 3", "/C.dropout", "/D.channels: preset OS1-64",
        "/E.rangeNoise"})
    CHECK(message.find(expected) != std::string::npos);
}

TEST_CASE("lidar: a USD stage's Lidar prim reads by the same attribute names as YAML", "[lidar]") {
  UsdImportReport report;
  const Scene scene = importUsdScene(SDG_SOURCE_DIR "/tests/data/lidar/sensor.usda", builtinRegistry().catalog(),
                                     UsdImportOptions{}, report);
  const Prim* prim = scene.stage.find("/World/Lidar");
  REQUIRE(prim);
  REQUIRE(prim->type() == PrimType::Lidar);
  CHECK(lidarProblems(*prim).empty());
  const LidarPattern p = lidarPatternOf(*prim);
  CHECK(p.elevations == std::vector<float>{-10, 0, 10});
  CHECK(p.solidState);
  CHECK(p.horizontalFov == 90.0f);
  CHECK(p.azimuths == 11);
  CHECK(p.rangeMin == 0.5f);
  CHECK(p.rangeMax == 40.0f);
  CHECK(p.rangeNoise == 0.02f);
  CHECK(scene.stage.worldMatrix(*prim).block<3, 1>(0, 3).isApprox(Vec3d(0, 0, 1)));
}
