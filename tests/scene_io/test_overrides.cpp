#include <catch2/catch.hpp>

#include "scene_fixtures.h"

using namespace sdg;
using sdg::test::errorsOf;
using sdg::test::loadText;

namespace {
const char* kScene = R"(
version: 1
writer: {type: BasicWriter}
prims:
  /Root: {}
  /Root/Cam: {type: Camera, translate: [0, 0, 5]}
  /Root/Box: {type: Cube, attributes: {user:mass: {type: double, value: 2}}}
)";
}

TEST_CASE("overrides: typed by the attribute or option they hit", "[scene_io][overrides]") {
  std::vector<std::string> sets = {"render.resolution=[640, 480]", "capture.frames=9", "writer.rgb=true",
                                   "writer.BasicWriter.frame_padding=6", "stage.metersPerUnit=0.01",
                                   "/Root/Cam.focalLength=35", "/Root/Cam.translate=[1,2,3]",
                                   "/Root/Box.user:mass=4.5"};
  Scene scene = loadText(kScene, {}, sets);
  CHECK(scene.render.get("resolution").get<Vec2i>() == Vec2i(640, 480));
  CHECK(scene.capture.getUInt("frames") == 9);
  CHECK(scene.writers[0].options.getBool("rgb"));
  CHECK(scene.writers[0].options.getUInt("frame_padding") == 6);
  CHECK(scene.stage.metadata().metersPerUnit == 0.01);
  CHECK(scene.stage.find("/Root/Cam")->getFloat("focalLength") == 35.0f);
  CHECK(scene.stage.find("/Root/Cam")->xformOps()[0].value.get<Vec3d>() == Vec3d(1, 2, 3));
  CHECK(scene.stage.find("/Root/Box")->findAttribute("user:mass")->value.get<double>() == 4.5);
}

TEST_CASE("overrides: errors point into the override text", "[scene_io][overrides]") {
  struct Case {
    std::vector<std::string> sets;
    const char* message;
  } cases[] = {
      {{"render.resolution=[640]"}, "--set[1]:1:19: error: render.resolution: expected a list of 2 integers"},
      {{"capture.frames=2", "render.resolutoin=[1,1]"}, "--set[2]:1:1: error: --set[2]: render has no option 'resolutoin' (did you mean 'resolution'?)"},
      {{"renderr.x=1"}, "unknown target 'renderr.x'"},
      {{"noequals"}, "expected TARGET=VALUE"},
      {{"/Root/Nope.size=1"}, "prim /Root/Nope does not exist"},
      {{"/Root/Box.sise=1"}, "Cube prim /Root/Box has no attribute 'sise' (did you mean 'size'?)"},
      {{"/Root/Box.rotateX=5"}, "the prim has no xformOp:rotateX op"},
      {{"/Root/Cam.focalLength=[1"}, "--set[1]:1:"},
      {{"/Root/Cam.clippingRange=[10, 1]"}, "expected 0 < near < far"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.sets);
    CHECK_THAT(errorsOf(kScene, {}, c.sets), Catch::Contains(c.message));
  }
}
