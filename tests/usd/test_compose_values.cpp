// Values resolved at the stage's start time code: time samples (held,
// interpolated), defaults, blocks, layer offsets of sublayers and references.
#include <catch2/catch.hpp>
#include <cmath>

#include "usd/compose_test_util.h"

using namespace sdg::usd;
using sdg::usd::test::MemoryLayers;
using sdg::usd::test::numberAt;
using sdg::usd::test::valueAt;

TEST_CASE("compose values: time samples at the start time code, interpolated where USD does", "[compose]") {
  MemoryLayers layers;
  layers.texts["root.usda"] = R"(#usda 1.0
(
    startTimeCode = 10
)
def "A"
{
    double d.timeSamples = { 0: 0, 20: 40 }
    double d = 99
    float3 v.timeSamples = { 0: (0, 0, 0), 20: (2, 4, 6) }
    int i.timeSamples = { 0: 1, 20: 3 }
    bool b.timeSamples = { 0: false, 20: true }
    token t.timeSamples = { 0: "a", 20: "b" }
    double before.timeSamples = { 15: 1, 30: 2 }
    double after.timeSamples = { 1: 5, 2: 6 }
    double exact.timeSamples = { 10: 8 }
    double blocked.timeSamples = { 0: None, 20: 5 }
    double gap.timeSamples = { 0: 1, 5: None, 20: 5 }
    quatf q.timeSamples = { 0: (1, 0, 0, 0), 20: (0, 0, 0, 1) }
    matrix4d m.timeSamples = { 0: ((1,0,0,0),(0,1,0,0),(0,0,1,0),(0,0,0,1)), 20: ((1,0,0,0),(0,1,0,0),(0,0,1,0),(10,0,0,1)) }
    float[] arr.timeSamples = { 0: [0, 0], 20: [2, 4] }
    float[] sizes.timeSamples = { 0: [0], 20: [2, 4] }
    double onlyDefault = 3
    double none = None
}
)";
  ComposedStage stage = layers.compose("root.usda");
  CHECK(stage.timeCode == 10);
  CHECK(numberAt(stage, "/A", "d") == 20);  // time samples win over the default in the same layer
  CHECK(stage.prim("/A")->property("d")->fromTimeSamples);
  CHECK(valueAt(stage, "/A", "v").numbers == std::vector<double>{1, 2, 3});
  CHECK(numberAt(stage, "/A", "i") == 1);  // integers are held, not interpolated
  CHECK_FALSE(valueAt(stage, "/A", "b").asBool());
  CHECK(valueAt(stage, "/A", "t").asString() == "a");
  CHECK(numberAt(stage, "/A", "before") == 1);  // before the first sample: the first
  CHECK(numberAt(stage, "/A", "after") == 6);   // after the last: the last
  CHECK(numberAt(stage, "/A", "exact") == 8);
  CHECK(valueAt(stage, "/A", "blocked").empty());  // a blocked sample is held, not interpolated
  CHECK(valueAt(stage, "/A", "gap").empty());  // the sample at 5 is a block, held until 20
  const Value& q = valueAt(stage, "/A", "q");  // slerp half way between identity and 180° about z
  REQUIRE(q.numbers.size() == 4);
  CHECK(q.numbers[0] == Approx(std::sqrt(0.5)));
  CHECK(q.numbers[3] == Approx(std::sqrt(0.5)));
  CHECK(valueAt(stage, "/A", "m").numbers[12] == 5);
  CHECK(valueAt(stage, "/A", "arr").numbers == std::vector<double>{1, 2});
  CHECK(valueAt(stage, "/A", "sizes").numbers == std::vector<double>{0});  // lengths differ: held
  CHECK(numberAt(stage, "/A", "onlyDefault") == 3);
  CHECK_FALSE(stage.prim("/A")->property("onlyDefault")->fromTimeSamples);
  CHECK(valueAt(stage, "/A", "none").empty());

  ComposeOptions at20;
  at20.timeCode = 20;
  CHECK(numberAt(layers.compose("root.usda", at20), "/A", "d") == 40);
}

TEST_CASE("compose values: a block in a stronger layer hides weaker values", "[compose]") {
  MemoryLayers layers;
  layers.texts["weak.usda"] = "#usda 1.0\ndef \"A\" { double x = 1\n double y.timeSamples = { 0: 2 } }\n";
  layers.texts["root.usda"] = "#usda 1.0\n(\n subLayers = [@weak.usda@]\n)\nover \"A\" { double x = None\n double y = 5 }\n";
  ComposedStage stage = layers.compose("root.usda");
  CHECK(valueAt(stage, "/A", "x").empty());
  CHECK(numberAt(stage, "/A", "y") == 5);  // the stronger layer's default beats weaker samples
}

TEST_CASE("compose values: sublayer and reference offsets map the stage's time", "[compose]") {
  MemoryLayers layers;
  layers.texts["anim.usda"] = R"(#usda 1.0
def "Anim" { double x.timeSamples = { 0: 0, 10: 100 } }
)";
  layers.texts["sub.usda"] = R"(#usda 1.0
def "S" { double x.timeSamples = { 0: 0, 10: 100 } }
)";
  layers.texts["root.usda"] = R"(#usda 1.0
(
    startTimeCode = 6
    subLayers = [@sub.usda@ (offset = 2; scale = 2)]
)
def "R" (references = @anim.usda@</Anim> (offset = 4)) {}
def "Scaled" (references = @anim.usda@</Anim> (scale = 0.5)) {}
)";
  ComposedStage stage = layers.compose("root.usda");
  CHECK(numberAt(stage, "/S", "x") == 20);       // stage 6 -> layer (6 - 2) / 2 = 2
  CHECK(numberAt(stage, "/R", "x") == 20);       // stage 6 -> layer 6 - 4 = 2
  CHECK(numberAt(stage, "/Scaled", "x") == 100);  // stage 6 -> layer 12: held at the last sample
}
