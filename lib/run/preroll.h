#pragma once
// The scene's pre-roll: for each event step, subscribe to the reply event,
// publish, then run updates until a reply containing `wait_for` arrives or
// `max_updates` updates have passed (the flag is read before each update and
// once more after the last, as Isaac Sim's helper does). A timeout is a
// RunError naming the event, the state waited for and the prim.
#include <span>

#include "behavior/runtime.h"
#include "scene_io/scene.h"

namespace sdg {

struct PrerollStepResult {
  std::string publish;
  uint64_t updates = 0;  // updates it took
};

std::vector<PrerollStepResult> runPreroll(std::span<const EventStep> steps, BehaviorRuntime& runtime);

}  // namespace sdg
