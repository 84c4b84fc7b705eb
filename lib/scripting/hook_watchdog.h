#pragma once
// The watchdog of calls into scripts (lifecycle hooks, event callbacks). A
// call that runs longer than the hook timeout is interrupted: a signal sent
// to the thread that runs scripts makes Python raise sdgbehave._HookTimeout
// in the script's code where it is (and ends a sleep or a blocking read),
// and the run fails (exit 1) naming the prim, behavior, hook, frame and the
// script's line. A call that does not respond within a grace period (a C
// loop that holds the interpreter, a script that catches the interruption
// and goes on) ends the process: the watchdog prints the same and exits 1.
// So no script hangs a run until a scheduler kills it.
//
// One watchdog thread per process, started by the first watched call. A
// watched call costs two short mutex holds and no wake-up of that thread.
#include <optional>
#include <string>

#include "core/source_loc.h"

namespace sdg::scripting {

// What the documentation promises when neither --hook-timeout nor
// run.hook_timeout says otherwise.
inline constexpr double kDefaultHookTimeout = 60.0;

// Seconds one call into a script may take; 0 turns the watchdog off.
void setHookTimeout(double seconds);
double hookTimeout();
// "did not return within 2 s (--hook-timeout, run.hook_timeout)"
std::string timeoutText();

// The signal the watchdog interrupts a call with; Python handles it
// (sdgbehave._on_hook_timeout), installed when the interpreter starts.
int watchdogSignal();
// Called by that handler on the script thread: whether the call the signal
// was sent for is still running (then it must raise), recording the script
// line it was at.
bool takeInterruption();

// One call into a script, on the thread that runs scripts. A call inside a
// watched call is covered by the outer one.
class WatchedCall {
 public:
  // `script`: the script's path as shown, named when no line can be read.
  // It must outlive the call.
  explicit WatchedCall(const std::string& script);
  ~WatchedCall();
  WatchedCall(const WatchedCall&) = delete;
  WatchedCall& operator=(const WatchedCall&) = delete;

  // Whether the watchdog interrupted this call, and the script line the
  // interruption found it at.
  bool timedOut() const;
  std::optional<SourceLoc> stuckAt() const;

 private:
  uint64_t id_ = 0;  // 0: not watched (no timeout, or inside another call)
};

}  // namespace sdg::scripting
