#pragma once
// Plays a stage's own animation (stage/stage_animation.h) on the timeline
// of a BehaviorRuntime. Precedence: the animation is the stage's authored
// motion and behaviors act on top of it. At each update while playing, every
// animated value is written at the timeline's time code first, then the
// behaviors run: a behavior that writes an animated attribute or op wins for
// the updates it writes, and the samples take over again at the next update
// it does not. Stopping puts back the values the stage had at play, after
// the behaviors' own on_stop restores, so the stage after stop equals the
// stage before play.
#include <cstdint>
#include <optional>
#include <vector>

#include "stage/stage.h"

namespace sdg {

class AnimationPlayback {
 public:
  explicit AnimationPlayback(Stage& stage) : stage_(stage) {}

  // Remembers the animated values as the stage holds them before play.
  void play();
  // Writes every animated value at the time code of the timeline's step
  // `steps` (updates since play) at `rate` updates a second.
  void update(uint64_t steps, double rate);
  // Writes back what play() remembered (nothing when not playing).
  void stop();

 private:
  Stage& stage_;
  bool playing_ = false;
  std::vector<std::optional<Value>> saved_;  // one per animated value; nullopt: nothing there at play
};

}  // namespace sdg
