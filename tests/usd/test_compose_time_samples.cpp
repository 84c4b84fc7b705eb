// The time samples composition keeps for playing a stage's animation
// (ComposedProperty::samples): their times on the stage's time line through
// layer offsets, and valueAt(t) equal to composing the stage at t.
#include <catch2/catch.hpp>

#include "usd/compose_test_util.h"

using namespace sdg::usd;
using sdg::usd::test::MemoryLayers;

namespace {

const AttributeSamples& samplesOf(const ComposedStage& stage, const std::string& prim, const std::string& name) {
  const ComposedPrim* p = stage.prim(prim);
  REQUIRE(p);
  const ComposedProperty* prop = p->property(name);
  REQUIRE(prop);
  REQUIRE(prop->samples);
  return *prop->samples;
}

}  // namespace

TEST_CASE("compose time samples: valueAt(t) is the stage composed at t", "[compose]") {
  MemoryLayers layers;
  layers.texts["anim.usda"] = R"(#usda 1.0
def "Anim" {
    double3 xformOp:translate.timeSamples = { 0: (0, 0, 0), 10: (10, 20, 30) }
    token visibility.timeSamples = { 0: "inherited", 4: "invisible", 7: "inherited" }
    int count.timeSamples = { 0: 1, 10: 5 }
    quatf orient.timeSamples = { 0: (1, 0, 0, 0), 10: (0, 0, 0, 1) }
    point3f[] points.timeSamples = { 0: [(0, 0, 0), (1, 0, 0)], 10: [(0, 0, 10), (1, 0, 10)] }
}
)";
  layers.texts["root.usda"] = R"(#usda 1.0
(
    startTimeCode = 2
    subLayers = [@anim.usda@ (offset = 2; scale = 2)]
)
def "Ref" (references = @anim.usda@</Anim> (offset = -5)) {}
)";
  const ComposedStage start = layers.compose("root.usda");
  // Sublayer: stage = 2 + 2 * layer; reference: stage = layer - 5.
  CHECK(samplesOf(start, "/Anim", "xformOp:translate").stageTimes() == std::vector<double>{2, 22});
  CHECK(samplesOf(start, "/Ref", "xformOp:translate").stageTimes() == std::vector<double>{-5, 5});
  CHECK(samplesOf(start, "/Anim", "visibility").stageTimes() == std::vector<double>{2, 10, 16});
  for (const char* prim : {"/Anim", "/Ref"})
    for (const char* name : {"xformOp:translate", "visibility", "count", "orient", "points"}) {
      const AttributeSamples& samples = samplesOf(start, prim, name);
      CHECK(samples.varies());
      for (double t : {-7.0, -5.0, 0.0, 2.0, 3.5, 9.999, 10.0, 12.25, 16.0, 30.0}) {
        ComposeOptions at;
        at.timeCode = t;
        const ComposedStage composed = layers.compose("root.usda", at);
        INFO(prim << "." << name << " at " << t);
        CHECK(samples.valueAt(t) == composed.prim(prim)->property(name)->value);
      }
    }
}

TEST_CASE("compose time samples: discrete values are held, numbers interpolated", "[compose]") {
  MemoryLayers layers;
  layers.texts["root.usda"] = R"(#usda 1.0
def "A" {
    double3 t.timeSamples = { 0: (0, 0, 0), 10: (10, 0, 0) }
    token visibility.timeSamples = { 0: "inherited", 5: "invisible" }
    bool flag.timeSamples = { 0: false, 10: true }
    double still.timeSamples = { 0: 3, 10: 3 }
    double blockedFirst.timeSamples = { 0: None, 10: 4 }
}
)";
  const ComposedStage stage = layers.compose("root.usda");
  const AttributeSamples& t = samplesOf(stage, "/A", "t");
  CHECK(t.valueAt(2.5).numbers == std::vector<double>{2.5, 0, 0});
  CHECK(t.valueAt(-1).numbers == std::vector<double>{0, 0, 0});
  CHECK(t.valueAt(11).numbers == std::vector<double>{10, 0, 0});
  const AttributeSamples& vis = samplesOf(stage, "/A", "visibility");
  CHECK(vis.valueAt(4.999).asString() == "inherited");
  CHECK(vis.valueAt(5).asString() == "invisible");
  CHECK(vis.valueAt(9).asString() == "invisible");
  CHECK_FALSE(samplesOf(stage, "/A", "flag").valueAt(9.9).asBool());
  CHECK_FALSE(samplesOf(stage, "/A", "still").varies());  // all alike: nothing to play
  // Blocked at the start time: no value now, but the samples are kept.
  CHECK(stage.prim("/A")->property("blockedFirst")->value.empty());
  CHECK(samplesOf(stage, "/A", "blockedFirst").valueAt(10).numbers == std::vector<double>{4});
}

TEST_CASE("compose time samples: a default in a stronger layer keeps no samples", "[compose]") {
  MemoryLayers layers;
  layers.texts["weak.usda"] = "#usda 1.0\ndef \"A\" { double y.timeSamples = { 0: 2, 10: 4 } }\n";
  layers.texts["root.usda"] = "#usda 1.0\n(\n subLayers = [@weak.usda@]\n)\nover \"A\" { double y = 5 }\n";
  const ComposedStage stage = layers.compose("root.usda");
  CHECK_FALSE(stage.prim("/A")->property("y")->samples);
}
