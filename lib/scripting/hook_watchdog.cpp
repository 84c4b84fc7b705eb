#include "scripting/hook_watchdog.h"

#include <pthread.h>
#include <unistd.h>

#include <csignal>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>

#include "behavior/run_activity.h"
#include "core/log.h"
#include "core/text.h"
#include "scripting/python_host.h"
#include "scripting/script_stack.h"

namespace sdg::scripting {
namespace {

using Clock = std::chrono::steady_clock;

struct Watch {
  std::mutex mutex;
  std::condition_variable wake;
  double timeout = kDefaultHookTimeout;
  bool threadStarted = false;
  uint64_t lastId = 0;
  uint64_t active = 0;  // the call being watched; 0: none
  const std::string* script = nullptr;
  Clock::time_point deadline;
  uint64_t interrupted = 0;  // the call the watchdog interrupted
  Clock::time_point graceEnd;
  std::optional<SourceLoc> stuckAt;
};

Watch& watch() {
  static auto* w = new Watch();  // used by a detached thread: never destroyed
  return *w;
}

Clock::duration seconds(double s) { return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s)); }

// How long an interrupted call may take to unwind before the process ends:
// as long as the timeout itself, between 1 and 5 seconds.
Clock::duration gracePeriod(double timeout) { return seconds(std::clamp(timeout, 1.0, 5.0)); }

// The call did not unwind: say where it is and end the process.
[[noreturn]] void giveUp(const std::string& script) {
  activity::Snapshot now = activity::current();
  std::optional<SourceLoc> line = runningScriptLine();
  std::string where = now.text().empty() ? "a script call" : now.text();
  log::error((line ? line->str() : script) + ": " + where + " " + timeoutText() +
             " and did not stop when interrupted (a loop in native code, or the script caught the interruption); "
             "sdgbehave exits");
  _exit(1);
}

void watchdogLoop() {
  Watch& w = watch();
  std::unique_lock lock(w.mutex);
  for (;;) {
    if (w.active == 0 || w.timeout <= 0) {
      // A call that starts now is seen within one timeout, before its
      // deadline: no call has to wake this thread.
      w.wake.wait_for(lock, w.timeout > 0 ? seconds(w.timeout) : std::chrono::hours(1));
      continue;
    }
    const Clock::time_point now = Clock::now();
    if (w.interrupted != w.active) {
      if (now < w.deadline) {
        w.wake.wait_until(lock, w.deadline);
        continue;
      }
      w.interrupted = w.active;
      w.graceEnd = now + gracePeriod(w.timeout);
      // Not Py_AddPendingCall: from another thread it does not wake the
      // interpreter's loop before Python 3.12.
      pthread_kill(scriptThread(), watchdogSignal());
      continue;
    }
    if (now < w.graceEnd) {
      w.wake.wait_until(lock, w.graceEnd);
      continue;
    }
    const std::string script = w.script ? *w.script : std::string("a script");
    lock.unlock();
    giveUp(script);
  }
}

}  // namespace

int watchdogSignal() { return SIGRTMAX - 3; }

bool takeInterruption() {
  std::optional<SourceLoc> where = runningScriptLine();
  Watch& w = watch();
  std::lock_guard lock(w.mutex);
  if (w.active == 0 || w.interrupted != w.active) return false;  // it returned meanwhile
  w.stuckAt = where;
  return true;
}

void setHookTimeout(double seconds) {
  Watch& w = watch();
  std::lock_guard lock(w.mutex);
  w.timeout = seconds;
  w.wake.notify_all();
}

double hookTimeout() {
  Watch& w = watch();
  std::lock_guard lock(w.mutex);
  return w.timeout;
}

std::string timeoutText() {
  return "did not return within " + text::formatNumber(hookTimeout()) + " s (--hook-timeout, run.hook_timeout)";
}

WatchedCall::WatchedCall(const std::string& script) {
  Watch& w = watch();
  std::lock_guard lock(w.mutex);
  if (w.timeout <= 0 || w.active != 0) return;
  if (!w.threadStarted) {
    std::thread(watchdogLoop).detach();
    w.threadStarted = true;
  }
  id_ = ++w.lastId;
  w.active = id_;
  w.script = &script;
  w.deadline = Clock::now() + seconds(w.timeout);
  w.stuckAt.reset();
}

WatchedCall::~WatchedCall() {
  if (!id_) return;
  Watch& w = watch();
  std::lock_guard lock(w.mutex);
  w.active = 0;
  w.script = nullptr;
}

bool WatchedCall::timedOut() const {
  if (!id_) return false;
  Watch& w = watch();
  std::lock_guard lock(w.mutex);
  return w.interrupted == id_;
}

std::optional<SourceLoc> WatchedCall::stuckAt() const {
  if (!id_) return std::nullopt;
  Watch& w = watch();
  std::lock_guard lock(w.mutex);
  return w.interrupted == id_ ? w.stuckAt : std::nullopt;
}

}  // namespace sdg::scripting
