#include <catch2/catch.hpp>

#include "stage/behavior_spec.h"
#include "stage/stage.h"

using namespace sdg;

TEST_CASE("stage: define, find, children order, remove subtree", "[stage]") {
  Stage stage;
  stage.definePrim("/Root", PrimType::Xform);
  stage.definePrim("/Root/B", PrimType::Cube);
  stage.definePrim("/Root/A", PrimType::Sphere);
  stage.definePrim("/Root/B/Child", PrimType::Cone);
  REQUIRE(stage.find("/Root/B"));
  const auto& children = stage.find("/Root")->children();
  REQUIRE(children.size() == 2);
  CHECK(children[0]->path() == "/Root/B");  // authored order, not sorted
  CHECK(stage.primCount() == 4);
  CHECK(stage.removePrim("/Root/B"));
  CHECK_FALSE(stage.find("/Root/B/Child"));
  CHECK(stage.primCount() == 2);
  CHECK_THROWS_AS(stage.definePrim("/Missing/X", PrimType::Xform), std::logic_error);
}

TEST_CASE("stage: schema fallbacks read through value()", "[stage]") {
  Stage stage;
  Prim& cam = stage.definePrim("/Cam", PrimType::Camera);
  CHECK(cam.getFloat("focalLength") == 50.0f);
  cam.setAttribute("focalLength", Value::makeFloat(24.0f));
  CHECK(cam.getFloat("focalLength") == 24.0f);
  Prim& sun = stage.definePrim("/Sun", PrimType::DistantLight);
  CHECK(sun.getFloat("inputs:intensity") == 50000.0f);  // UsdLux DistantLight fallback
  CHECK(cam.value("nope") == nullptr);
}

TEST_CASE("stage: copies are deep and compare equal until changed", "[stage]") {
  Stage stage;
  stage.definePrim("/Root", PrimType::Xform).semantics()["class"] = {"thing"};
  stage.definePrim("/Root/Box", PrimType::Cube).setAttribute("size", Value::makeDouble(3.0));
  Stage copy = stage;
  CHECK(copy == stage);
  copy.find("/Root/Box")->setAttribute("size", Value::makeDouble(4.0));
  CHECK_FALSE(copy == stage);
  CHECK(stage.find("/Root/Box")->getDouble("size") == 3.0);
}

TEST_CASE("stage: exposed variables keep authored values", "[stage][behavior]") {
  BehaviorSpec spec;
  spec.name = "demo";
  AttributeSpec interval;
  interval.name = "interval";
  interval.type = ValueType::UInt;
  interval.defaultValue = Value::makeUInt(0);
  spec.variables = {interval};
  Stage stage;
  Prim& p = stage.definePrim("/P", PrimType::Xform);
  p.setAttribute("exposedVar:demo:interval", Value::makeUInt(5), true);
  createExposedVariables(p, spec);
  CHECK(p.findAttribute("exposedVar:demo:interval")->value.get<uint32_t>() == 5);
  removeExposedVariables(p, spec);
  CHECK_FALSE(p.findAttribute("exposedVar:demo:interval"));
  createExposedVariables(p, spec);
  CHECK(p.findAttribute("exposedVar:demo:interval")->value.get<uint32_t>() == 0);
}
