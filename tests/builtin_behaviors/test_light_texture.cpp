#include "behavior/behavior_fixtures.h"

using namespace sdg;

TEST_CASE("lightRandomizer: colours and intensities in range, lights only, restored on stop",
          "[behaviors][light]") {
  test::BehaviorScene s(R"(
version: 1
prims:
  /Lights:
    behaviors:
      lightRandomizer: {range:minColor: [0.2, 0.3, 0.4], range:maxColor: [0.5, 0.6, 0.7], range:intensity: [100, 200]}
  /Lights/Sun: {type: DistantLight, inputs:intensity: 4000}
  /Lights/Bulb: {type: SphereLight}
  /Lights/NotALight: {type: Cube}
)");
  Stage before = s.stage();
  s.runtime->play();
  for (int i = 0; i < 1000; ++i) {
    s.runtime->update();
    for (const char* path : {"/Lights/Sun", "/Lights/Bulb"}) {
      const Prim& light = s.prim(path);
      Vec3f c = light.findAttribute("inputs:color")->value.get<Vec3f>();
      float intensity = light.findAttribute("inputs:intensity")->value.get<float>();
      REQUIRE(c.x() >= 0.2f);
      REQUIRE(c.x() <= 0.5f);
      REQUIRE(c.y() >= 0.3f);
      REQUIRE(c.z() <= 0.7f);
      REQUIRE(intensity >= 100.0f);
      REQUIRE(intensity <= 200.0f);
    }
  }
  CHECK_FALSE(s.prim("/Lights/NotALight").findAttribute("inputs:color"));
  s.runtime->stop();
  CHECK(s.stage() == before);  // authored intensity back, created attributes gone
  CHECK(s.prim("/Lights/Sun").getFloat("inputs:intensity") == 4000.0f);
  CHECK_FALSE(s.prim("/Lights/Bulb").findAttribute("inputs:intensity"));
}

TEST_CASE("textureRandomizer: one material per geometry prim, random inputs, exact restore",
          "[behaviors][texture]") {
  test::BehaviorScene s(R"(
version: 1
prims:
  /Looks: {type: Scope}
  /Looks/Paint: {type: Material}
  /Group:
    material: /Looks/Paint
    behaviors:
      textureRandomizer: {textures:csv: "textures/wood.png, textures/bamboo.png", textureScaleRange: [0.5, 2], textureRotateRange: [10, 20]}
  /Group/A: {type: Cube}
  /Group/B: {type: Sphere, material: /Looks/Paint}
  /Group/Light: {type: SphereLight}
)");
  Stage before = s.stage();
  s.runtime->play();
  const Prim& a = s.prim("/Group/A");
  REQUIRE(a.material());
  CHECK(a.material()->strength == "strongerThanDescendants");
  CHECK(a.material()->path.rfind("/Behaviors/textureRandomizer/Looks/OmniPBR_", 0) == 0);
  CHECK(s.prim("/Group/B").material()->path != a.material()->path);
  CHECK_FALSE(s.prim("/Group/Light").material());
  int projected = 0;
  const int n = 2000;
  for (int i = 0; i < n; ++i) {
    s.runtime->update();
    const Prim& m = s.prim(a.material()->path);
    const std::string& tex = m.findAttribute("inputs:diffuse_texture")->value.get<std::string>();
    REQUIRE((tex == "textures/wood.png" || tex == "textures/bamboo.png"));
    Vec2f scale = m.findAttribute("inputs:texture_scale")->value.get<Vec2f>();
    REQUIRE(scale.x() == scale.y());
    REQUIRE(scale.x() >= 0.5f);
    REQUIRE(scale.x() <= 2.0f);
    float rotate = m.findAttribute("inputs:texture_rotate")->value.get<float>();
    REQUIRE(rotate >= 10.0f);
    REQUIRE(rotate <= 20.0f);
    projected += m.findAttribute("inputs:project_uvw")->value.get<bool>();
  }
  // projectUvwProbability 0.9: binomial, within 5 sigma.
  CHECK(std::abs(projected - 0.9 * n) < 5 * std::sqrt(n * 0.9 * 0.1));
  s.runtime->stop();
  CHECK(s.stage() == before);  // bindings exactly as before, /Behaviors gone
}

TEST_CASE("textureRandomizer: a missing texture file is an error naming it and the places searched",
          "[behaviors][texture]") {
  test::BehaviorScene s(R"(
version: 1
prims:
  /A: {type: Cube, behaviors: {textureRandomizer: {textures:csv: "textures/nope.png"}}}
)");
  CHECK_THROWS_WITH(s.runtime->play(), Catch::Contains("texture 'textures/nope.png' not found; searched:") &&
                                           Catch::Contains("scenes/textures/nope.png"));
}

TEST_CASE("textureRandomizer: an empty texture list skips every apply", "[behaviors][texture]") {
  test::BehaviorScene s(R"(
version: 1
prims:
  /A: {type: Cube, behaviors: {textureRandomizer: {textures:csv: ""}}}
)");
  s.runtime->play();
  Stage afterPlay = s.stage();
  s.runtime->update();
  CHECK(s.stage() == afterPlay);
}
