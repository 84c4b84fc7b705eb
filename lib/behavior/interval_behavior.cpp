#include "behavior/interval_behavior.h"

namespace sdg {

void IntervalBehavior::onPlay() {
  interval_ = var<uint32_t>("interval");
  setup();
  setUp_ = true;
  if (interval_ > 0) apply();  // the first captured frame is already randomised
}

void IntervalBehavior::onUpdate(double, double dt) {
  if (dt <= 0) return;
  if (interval_ == 0) {
    apply();
    return;
  }
  if (++counter_ >= interval_) {
    apply();
    counter_ = 0;
  }
}

void IntervalBehavior::onStop() {
  if (setUp_) restore();
  setUp_ = false;
  counter_ = 0;
  interval_ = 0;
}

void IntervalBehavior::onDestroy() { onStop(); }

}  // namespace sdg
