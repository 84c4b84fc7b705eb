// BehaviorRuntime::attach: a behavior started on a running stage (what a
// driver program does when it lists a script on a prim) gets its exposed
// variables, onInit, and onPlay when the timeline already plays.
#include <catch2/catch.hpp>

#include "behavior/behavior_fixtures.h"

namespace sdg::test {

TEST_CASE("attaching after init starts the behavior like one attached at init", "[behavior][runtime]") {
  BehaviorScene s(R"(
version: 1
prims:
  /World: {}
  /World/Box: {type: Cube, translate: [1, 2, 3]}
)");
  Prim& box = s.prim("/World/Box");
  REQUIRE(box.value("exposedVar:locationRandomizer:interval") == nullptr);
  box.behaviors().push_back("locationRandomizer");
  s.runtime->attach(box, "locationRandomizer");
  CHECK(box.value("exposedVar:locationRandomizer:interval") != nullptr);  // its variables, with defaults
  CHECK(s.runtime->behaviorCount() == 1);
  const Vec3d start = s.translate("/World/Box");
  s.runtime->play();
  s.runtime->update();
  CHECK_FALSE(s.translate("/World/Box").isApprox(start));  // it randomizes once playing
  s.runtime->stop();
  CHECK(s.translate("/World/Box").isApprox(start));  // and restores on stop
}

TEST_CASE("attaching while playing plays the behavior at once", "[behavior][runtime]") {
  BehaviorScene s(R"(
version: 1
prims:
  /World: {}
  /World/Box: {type: Cube, translate: [0, 0, 0]}
)");
  s.runtime->play();
  Prim& box = s.prim("/World/Box");
  const Vec3d start = s.translate("/World/Box");
  s.runtime->attach(box, "locationRandomizer");
  s.runtime->update();
  CHECK_FALSE(s.translate("/World/Box").isApprox(start));
  CHECK_THROWS_AS(s.runtime->attach(box, "noSuchBehavior"), std::logic_error);
}

}  // namespace sdg::test
