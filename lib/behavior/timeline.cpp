#include "behavior/timeline.h"

namespace sdg {

bool Timeline::play() {
  if (state_ == State::Playing) return false;
  state_ = State::Playing;
  return true;
}

bool Timeline::pause() {
  if (state_ != State::Playing) return false;
  state_ = State::Paused;
  return true;
}

bool Timeline::stop() {
  if (state_ == State::Stopped) return false;
  state_ = State::Stopped;
  steps_ = 0;
  return true;
}

double Timeline::advance() {
  if (state_ != State::Playing) return 0.0;
  ++steps_;
  return dt_;
}

}  // namespace sdg
