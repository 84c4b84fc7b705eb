#pragma once
// The timeline: stopped, playing or paused; each update advances the time by
// 1 / timeCodesPerSecond while playing. The time is the number of steps
// since play divided by the rate, never a running sum of steps, so it does
// not drift: step 10000 at 60 per second is exactly 10000 / 60.
#include <cstdint>

namespace sdg {

class Timeline {
 public:
  enum class State { Stopped, Playing, Paused };

  explicit Timeline(double timeCodesPerSecond = 60.0) : rate_(timeCodesPerSecond), dt_(1.0 / timeCodesPerSecond) {}
  State state() const { return state_; }
  bool playing() const { return state_ == State::Playing; }
  double time() const { return double(steps_) / rate_; }
  double stepSize() const { return dt_; }
  double rate() const { return rate_; }  // updates a second
  // Steps taken since the timeline last started playing from a stop.
  uint64_t steps() const { return steps_; }

  // Each returns true when the state changed (the hooks must run).
  bool play();
  bool pause();
  bool stop();
  // Advances the time when playing; returns the dt to hand to behaviors
  // (0 when not playing).
  double advance();

 private:
  State state_ = State::Stopped;
  uint64_t steps_ = 0;
  double rate_;
  double dt_;
};

}  // namespace sdg
