// Optical flow from poses (writers/motion.h) on synthetic frames: a plane
// facing the camera that moves, a camera that moves, the sky, and the
// cases without a place in the other frame.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "writers/motion.h"

using namespace sdg;

namespace {

constexpr int kW = 64, kH = 48;
constexpr double kDistance = 10.0;  // metres from the camera to the plane

RenderList sceneWith(const Vec3d& plane, const Vec3d& eye) {
  RenderList list;
  RenderCamera camera;
  camera.path = "/Camera";
  camera.worldFromCamera.block<3, 1>(0, 3) = eye;  // looking down -Z
  list.cameras.push_back(camera);
  RenderItem item;
  item.primPath = "/Plane";
  item.instanceId = 1;
  item.worldFromLocal.block<3, 1>(0, 3) = plane;
  list.items.push_back(item);
  return list;
}

FramePasses planeEverywhere() {
  FramePasses passes;
  passes.width = kW;
  passes.height = kH;
  passes.instanceIds.assign(size_t(kW) * kH, 1);
  passes.distanceToImagePlane.assign(size_t(kW) * kH, float(kDistance));
  return passes;
}

double focalPixels() { return 50.0 / 20.955 * kW; }  // RenderCamera's defaults

}  // namespace

TEST_CASE("flow: a plane moving across the view moves every pixel by f * step / depth", "[writers][motion]") {
  const RenderList now = sceneWith({0, 0, 0}, {0, 0, kDistance});
  const RenderList next = sceneWith({1, 0.5, 0}, {0, 0, kDistance});
  std::vector<float> flow;
  flowTo(planeEverywhere(), now, now.cameras[0], 1.0, &next, flow);
  REQUIRE(flow.size() == size_t(kW) * kH * 2);
  for (size_t i = 0; i < size_t(kW) * kH; i += 97) {
    CHECK(flow[i * 2] == Approx(-0.5 * focalPixels() / kDistance).margin(1e-3));  // up the image: row decreases
    CHECK(flow[i * 2 + 1] == Approx(1.0 * focalPixels() / kDistance).margin(1e-3));
  }
}

TEST_CASE("flow: a moving camera moves the plane the other way and leaves the sky", "[writers][motion]") {
  const RenderList now = sceneWith({0, 0, 0}, {0, 0, kDistance});
  const RenderList next = sceneWith({0, 0, 0}, {0.5, 0, kDistance});
  FramePasses passes = planeEverywhere();
  passes.instanceIds[0] = 0;  // one pixel of sky
  passes.distanceToImagePlane[0] = std::numeric_limits<float>::infinity();
  std::vector<float> flow;
  flowTo(passes, now, now.cameras[0], 1.0, &next, flow);
  CHECK(flow[2 * 5 + 1] == Approx(-0.5 * focalPixels() / kDistance).margin(1e-3));
  CHECK(flow[0] == Approx(0.0).margin(1e-5));  // translation does not move directions at infinity
  CHECK(flow[1] == Approx(0.0).margin(1e-5));
  // Scene units of 1 cm: the same depth in metres is 100 times farther away.
  std::vector<float> centimetres;
  flowTo(passes, now, now.cameras[0], 0.01, &next, centimetres);
  CHECK(centimetres[2 * 5 + 1] == Approx(-0.5 * focalPixels() / (kDistance * 100)).margin(1e-4));
}

TEST_CASE("flow: the sky turns with the camera", "[writers][motion]") {
  RenderList now = sceneWith({0, 0, 0}, {0, 0, kDistance});
  RenderList next = now;
  // A small turn about the camera's vertical axis: the sky slides sideways.
  next.cameras[0].worldFromCamera.block<3, 3>(0, 0) = Eigen::AngleAxisd(0.02, Vec3d::UnitY()).toRotationMatrix();
  FramePasses passes = planeEverywhere();
  const size_t centre = size_t(kH / 2) * kW + kW / 2;
  passes.instanceIds[centre] = 0;
  std::vector<float> flow;
  flowTo(passes, now, now.cameras[0], 1.0, &next, flow);
  // Turning left (about +Y) moves what is ahead to the right by about f * angle.
  CHECK(flow[centre * 2 + 1] == Approx(focalPixels() * std::tan(0.02)).epsilon(0.02));
}

TEST_CASE("flow: zero where the point has no place in the other frame", "[writers][motion]") {
  const RenderList now = sceneWith({0, 0, 0}, {0, 0, kDistance});
  std::vector<float> flow;
  flowTo(planeEverywhere(), now, now.cameras[0], 1.0, nullptr, flow);  // the first or last frame
  CHECK(std::all_of(flow.begin(), flow.end(), [](float v) { return v == 0.0f; }));
  RenderList gone = sceneWith({1, 0, 0}, {0, 0, kDistance});
  gone.items[0].primPath = "/Other";
  flowTo(planeEverywhere(), now, now.cameras[0], 1.0, &gone, flow);
  CHECK(std::all_of(flow.begin(), flow.end(), [](float v) { return v == 0.0f; }));
  RenderList behind = sceneWith({0, 0, 2 * kDistance}, {0, 0, kDistance});  // the plane passed the camera
  flowTo(planeEverywhere(), now, now.cameras[0], 1.0, &behind, flow);
  CHECK(std::all_of(flow.begin(), flow.end(), [](float v) { return v == 0.0f; }));
}
