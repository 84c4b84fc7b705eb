// The frames at which a randomizer applies, for several intervals and across
// pause/resume (spec §1.5).
#include "behavior/behavior_fixtures.h"

using namespace sdg;

namespace {
// Runs `steps`: 'p' play, 'u' update, 's' pause, 'x' stop. Returns the
// indices of the steps after which the box's translate changed.
std::vector<int> changes(uint32_t interval, const std::string& steps) {
  test::BehaviorScene s("version: 1\nprims:\n  /Box:\n    type: Cube\n    translate: [0, 0, 0]\n    behaviors:\n      locationRandomizer: {interval: " +
                        std::to_string(interval) + "}\n");
  std::vector<int> changed;
  Stage before = s.stage();
  for (size_t i = 0; i < steps.size(); ++i) {
    switch (steps[i]) {
      case 'p': s.runtime->play(); break;
      case 'u': s.runtime->update(); break;
      case 's': s.runtime->pause(); break;
      case 'x': s.runtime->stop(); break;
    }
    if (!diffStages(before, s.stage()).empty()) changed.push_back(static_cast<int>(i));
    before = s.stage();
  }
  return changed;
}
}  // namespace

TEST_CASE("interval 0: every update applies, play does not", "[behaviors][interval]") {
  CHECK(changes(0, "puuu") == std::vector<int>{1, 2, 3});
}

TEST_CASE("interval 1: play applies, then every update", "[behaviors][interval]") {
  CHECK(changes(1, "puuu") == std::vector<int>{0, 1, 2, 3});
}

TEST_CASE("interval 3: play applies, then every third update", "[behaviors][interval]") {
  CHECK(changes(3, "puuuuuuu") == std::vector<int>{0, 3, 6});
}

TEST_CASE("interval 3 across pause/resume: updates while paused do not count and resume applies once",
          "[behaviors][interval]") {
  // play(0) u1 u2 pause(3) u4 u5 play(6: applies) u7 (counter 3: applies) u8 u9 u10 (applies)
  CHECK(changes(3, "puusuupuuuu") == std::vector<int>{0, 6, 7, 10});
}

TEST_CASE("stop restores and resets the counter", "[behaviors][interval]") {
  // play(0) u1 u2 stop(3: restore) play(4) u5 u6 u7 (applies: the counter restarted)
  CHECK(changes(3, "puuxpuuu") == std::vector<int>{0, 3, 4, 7});
}
