#pragma once
// A run without pixels: pre-roll, then play and one update per frame, then
// stop and destroy. `run --no-render --record` uses it to debug scenes; the
// behavior tests use it to check behaviors end to end.
#include <cstdint>
#include <string>

#include "run/scene_setup.h"

namespace sdg {

struct TimelineRunOptions {
  uint64_t frames = 1;
  int64_t seed = 0;
  std::string recordPath;  // "" = no record
  std::string saveStagePath;  // "" = none
};

struct TimelineRunResult {
  uint64_t frames = 0;
  uint64_t updates = 0;
  size_t behaviors = 0;
  bool stageRestored = false;
  std::vector<nlohmann::ordered_json> settle;  // one report per stacked surface  // the stage after stop equals the stage before play
};

TimelineRunResult runTimeline(LoadedScene& loaded, const TimelineRunOptions& options);

}  // namespace sdg
