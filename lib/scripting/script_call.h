#pragma once
// A call into a script during a run (a lifecycle hook, an event callback):
// watched by the hook watchdog, and whatever goes wrong in it becomes a
// RunError (exit 1) at the script's file:line naming `where` (the prim, the
// behavior and the hook) and the frame: an exception (with its traceback),
// a timeout, or sys.exit() and os._exit(), which a script may not use to
// end the run.
#include <string>

#include <pybind11/pybind11.h>

#include "scripting/hook_watchdog.h"

namespace sdg::scripting {

// "sys.exit(0)" or "os._exit(1)" when `error` is a script's attempt to end
// the process, else "".
std::string exitCall(pybind11::error_already_set& error);

[[noreturn]] void throwScriptCallError(pybind11::error_already_set& error, const std::string& where,
                                       const WatchedCall& call);
// The call returned although the watchdog interrupted it (the script caught
// the interruption).
[[noreturn]] void throwCaughtTimeout(const std::string& script, const std::string& where, const WatchedCall& call);

// Runs `call()`; `where()` builds the description only when it is needed.
template <typename Call, typename Where>
void callScript(const std::string& script, Where&& where, Call&& call) {
  WatchedCall watch(script);
  try {
    call();
  } catch (pybind11::error_already_set& e) {
    throwScriptCallError(e, where(), watch);
  }
  if (watch.timedOut()) throwCaughtTimeout(script, where(), watch);
}

}  // namespace sdg::scripting
