#pragma once
// Base of the timeline-driven randomizers: the `interval` counting of the
// Isaac Sim behaviors (an update counter; 0 = every update; a dt <= 0 update
// is ignored and not counted; one apply on every play when interval > 0,
// resume from pause included; the counter survives pause and resets on stop)
// and the setup / apply / restore split.
#include "behavior/behavior.h"

namespace sdg {

class IntervalBehavior : public Behavior {
 public:
  void onPlay() final;
  void onUpdate(double time, double dt) final;
  void onStop() final;
  void onDestroy() final;

  uint32_t updateCounter() const { return counter_; }

 protected:
  // Re-reads the exposed variables on every play; builds caches (random
  // stream, prims, initial values) only when not set up since the last stop.
  virtual void setup() = 0;
  virtual void apply() = 0;
  // Writes back what the behavior changed and forgets its caches.
  virtual void restore() = 0;
  bool isSetUp() const { return setUp_; }
  void markSetUp() { setUp_ = true; }

 private:
  uint32_t interval_ = 0;
  uint32_t counter_ = 0;
  bool setUp_ = false;
};

}  // namespace sdg
