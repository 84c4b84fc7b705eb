// Bad behavior input: located messages that name what is wrong.
#include "behavior/behavior_fixtures.h"

#include "../scene_io/scene_fixtures.h"

using namespace sdg;

TEST_CASE("behavior errors: unknown names, variables, types, ranges and targets", "[behaviors][errors]") {
  const BehaviorCatalog catalog = builtinRegistry().catalog();
  struct Case {
    const char* behaviors;
    const char* message;
  } cases[] = {
      {"{locationRandomiser: {}}",
       "t.yaml:4:32: error: /A: unknown behavior 'locationRandomiser'; known behaviors: locationRandomizer, "
       "rotationRandomizer, lookAtBehavior, lightRandomizer, textureRandomizer, volumeStackRandomizer (did you mean "
       "'locationRandomizer'?)"},
      {"{locationRandomizer: {intervall: 2}}",
       "/A locationRandomizer: unknown key 'intervall' (did you mean 'interval'?)"},
      {"{locationRandomizer: {interval: -1}}",
       "t.yaml:4:63: error: /A.exposedVar:locationRandomizer:interval: -1 is out of range (0 to 4294967295)"},
      {"{locationRandomizer: {range:minPosition: [0, 0]}}",
       "/A.exposedVar:locationRandomizer:range:minPosition: expected a list of 3 numbers, found a list of 2 items"},
      {"{locationRandomizer: {range:minPosition: [0, 5, 0], range:maxPosition: [1, 1, 1]}}",
       "/A: exposedVar:locationRandomizer:range:minPosition (5) is greater than "
       "exposedVar:locationRandomizer:range:maxPosition (1) in y"},
      {"{lightRandomizer: {range:intensity: [10, 1]}}",
       "exposedVar:lightRandomizer:range:intensity: the minimum 10 is greater than the maximum 1"},
      {"{lookAtBehavior: {targetPrimPath: /Nowhere}}",
       "/A.exposedVar:lookAtBehavior:targetPrimPath: prim '/Nowhere' does not exist"},
      {"{textureRandomizer: {projectUvwProbability: 1.5}}", "a probability is at most 1, found 1.5"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.behaviors);
    std::string yaml = "version: 1\nprims:\n  /Root: {}\n  /A: {type: Cube, behaviors: " + std::string(c.behaviors) + "}\n";
    CHECK_THAT(test::errorsOf(yaml, catalog), Catch::Contains(c.message));
  }
}

TEST_CASE("behavior errors: --set on an exposed variable is typed by its spec", "[behaviors][errors]") {
  const BehaviorCatalog catalog = builtinRegistry().catalog();
  std::string yaml = "version: 1\nprims:\n  /A: {type: Cube, behaviors: {locationRandomizer: {}}}\n";
  std::vector<std::string> ok = {"/A.exposedVar:locationRandomizer:interval=5"};
  Scene scene = test::loadText(yaml, catalog, ok);
  CHECK(scene.stage.find("/A")->findAttribute("exposedVar:locationRandomizer:interval")->value.get<uint32_t>() == 5);
  std::vector<std::string> bad = {"/A.exposedVar:locationRandomizer:interval=-2"};
  CHECK_THAT(test::errorsOf(yaml, catalog, bad), Catch::Contains("--set[1]:1:43: error: /A.exposedVar:locationRandomizer:interval: -2 is out of range"));
}
