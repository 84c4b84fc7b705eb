#pragma once
// Runs the behaviors of a stage: one instance per (prim, attached behavior),
// in stage pre-order and, per prim, in the order the scene lists them. Each
// update first delivers queued events, then (while playing) writes the
// stage's own animation at the new time (animation_playback.h) and calls
// onUpdate.
// Stopping delivers what is still queued first (the events published in
// the last update), so no event is lost at the end of a run. Every hook
// call is recorded in run_activity for messages about a stuck or
// interrupted run.
#include <memory>
#include <vector>

#include "behavior/animation_playback.h"
#include "behavior/behavior.h"
#include "behavior/event_bus.h"
#include "behavior/registry.h"
#include "behavior/run_activity.h"
#include "behavior/timeline.h"

namespace sdg {

class BehaviorRuntime {
 public:
  BehaviorRuntime(Stage& stage, const BehaviorRegistry& registry, BehaviorContext context);
  ~BehaviorRuntime();
  BehaviorRuntime(const BehaviorRuntime&) = delete;
  BehaviorRuntime& operator=(const BehaviorRuntime&) = delete;

  // Instantiates every attached behavior and calls onInit.
  void init();
  // Attaches behavior `name` to `prim` after init (a driver program listing
  // a script on a prim, `sdgbehave exec`): its exposed variables, onInit,
  // and onPlay when the timeline plays.
  void attach(Prim& prim, const std::string& name);
  void play();
  void pause();
  // Delivers the events still queued (the timeline still playing), then
  // onStop in reverse order.
  void stop();
  // One app update: events, then onUpdate(time, dt) while playing.
  void update();
  // onDestroy for every behavior (stopping first if needed); idempotent.
  void destroy();

  EventBus& events() { return events_; }
  const Timeline& timeline() const { return timeline_; }
  size_t behaviorCount() const { return behaviors_.size(); }
  uint64_t updateCount() const { return updates_; }

 private:
  Stage& stage_;
  const BehaviorRegistry& registry_;
  BehaviorContext context_;
  EventBus events_;
  Timeline timeline_;
  AnimationPlayback animation_;  // the stage's own animation, under the behaviors
  std::vector<std::unique_ptr<Behavior>> behaviors_;
  uint64_t updates_ = 0;
  uint64_t prerollUpdates_ = 0;

  // onStop in reverse order, without delivering queued events (a failed
  // run's clean-up must not run more script code than it has to).
  void stopHooks();
  // The frame the timeline's step `step` (0-based) renders, for messages.
  void notePhase(activity::Phase phase, uint64_t step) const;
  bool destroyed_ = false;
};

}  // namespace sdg
