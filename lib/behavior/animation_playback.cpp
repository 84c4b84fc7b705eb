#include "behavior/animation_playback.h"

namespace sdg {

void AnimationPlayback::play() {
  if (playing_) return;  // resumed after a pause: what play saw is still what stop restores
  playing_ = true;
  saved_.clear();
  for (const auto& animated : stage_.animation().values()) saved_.push_back(readAnimatedTarget(stage_, *animated));
}

void AnimationPlayback::update(uint64_t steps, double rate) {
  for (const auto& animated : stage_.animation().values())
    writeAnimatedValue(stage_, *animated, animated->at(timeCodeAt(animated->clock, steps, rate)));
}

void AnimationPlayback::stop() {
  if (!playing_) return;
  playing_ = false;
  const auto& values = stage_.animation().values();
  for (size_t i = 0; i < values.size() && i < saved_.size(); ++i) {
    if (saved_[i]) {
      writeAnimatedValue(stage_, *values[i], *saved_[i]);
    } else if (!values[i]->xformOp) {
      // Not authored before play: authored by the samples, so removed again.
      if (Prim* prim = stage_.find(values[i]->primPath)) prim->removeAttribute(values[i]->name);
    }
  }
  saved_.clear();
}

}  // namespace sdg
