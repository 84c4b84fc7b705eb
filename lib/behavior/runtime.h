#pragma once
// Runs the behaviors of a stage: one instance per (prim, attached behavior),
// in stage pre-order and, per prim, in the order the scene lists them. Each
// update first delivers queued events, then (while playing) calls onUpdate.
#include <memory>
#include <vector>

#include "behavior/behavior.h"
#include "behavior/event_bus.h"
#include "behavior/registry.h"
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
  void play();
  void pause();
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
  std::vector<std::unique_ptr<Behavior>> behaviors_;
  uint64_t updates_ = 0;
  bool destroyed_ = false;
};

}  // namespace sdg
