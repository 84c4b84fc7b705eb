#pragma once
// The timeline: stopped, playing or paused; each update advances the time by
// 1 / timeCodesPerSecond while playing.
namespace sdg {

class Timeline {
 public:
  enum class State { Stopped, Playing, Paused };

  explicit Timeline(double timeCodesPerSecond = 60.0) : dt_(1.0 / timeCodesPerSecond) {}
  State state() const { return state_; }
  bool playing() const { return state_ == State::Playing; }
  double time() const { return time_; }
  double stepSize() const { return dt_; }

  // Each returns true when the state changed (the hooks must run).
  bool play();
  bool pause();
  bool stop();
  // Advances the time when playing; returns the dt to hand to behaviors
  // (0 when not playing).
  double advance();

 private:
  State state_ = State::Stopped;
  double time_ = 0.0;
  double dt_;
};

}  // namespace sdg
