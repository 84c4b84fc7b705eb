#pragma once
// A progress bar on stderr when it is a terminal: frames, frames/s and ETA,
// redrawn in place at most 10 times a second. When stderr is not a terminal
// (logs, schedulers) it prints nothing; the run's log lines stand alone.
#include <chrono>
#include <cstdint>

namespace sdg {

class Progress {
 public:
  Progress(uint64_t total, bool enabled);
  void update(uint64_t done);
  void finish();
  static bool stderrIsTerminal();

 private:
  uint64_t total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_, lastDraw_;
};

}  // namespace sdg
