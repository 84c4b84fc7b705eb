#include "run/preroll.h"

#include "core/diagnostics.h"
#include "core/log.h"

namespace sdg {

std::vector<PrerollStepResult> runPreroll(std::span<const EventStep> steps, BehaviorRuntime& runtime) {
  std::vector<PrerollStepResult> results;
  EventBus& bus = runtime.events();
  for (const EventStep& step : steps) {
    bool complete = step.waitFor.empty() && step.waitEvent.empty();
    EventBus::Subscription subscription = 0;
    if (!step.waitEvent.empty())
      subscription = bus.subscribe(step.waitEvent, [&](const Payload& reply) {
        if (reply.contains(step.waitFor)) complete = true;
      });
    log::debug("pre-roll: publish " + step.publish + " " + step.payload.toString());
    bus.publish(step.publish, step.payload);
    uint64_t updates = 0;
    // With nothing to wait for, one update delivers the event.
    uint32_t budget = step.waitEvent.empty() ? 1 : step.maxUpdates;
    for (uint32_t i = 0; i < budget; ++i) {
      if (complete && !step.waitEvent.empty()) break;
      runtime.update();
      ++updates;
    }
    if (subscription) bus.unsubscribe(subscription);
    if (!step.waitEvent.empty() && !complete) {
      std::string_view prim = step.payload.getString("prim_path");
      throw RunError(step.loc.str() + ": pre-roll: published " + step.publish + " " + step.payload.toString() +
                     " but no reply on " + step.waitEvent + " matched " + step.waitFor.toString() + " within " +
                     std::to_string(step.maxUpdates) + " updates (prim: " +
                     (prim.empty() ? std::string("all prims") : std::string(prim)) + ")");
    }
    results.push_back({step.publish, updates});
  }
  return results;
}

}  // namespace sdg
