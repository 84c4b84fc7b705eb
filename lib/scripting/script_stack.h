#pragma once
// Where the scripts' Python code is right now, read from any thread and
// without the interpreter lock, as Python's faulthandler reads it: the hook
// watchdog and the stop-signal handler name the script line a stuck or
// interrupted run was at, even when the code holds the lock in a C loop.
#include <optional>

#include "core/source_loc.h"

namespace sdg::scripting {

// The innermost frame of the script thread's Python stack that is in a
// loaded script (else its innermost frame), as file:line with the script's
// path as given; nullopt when no Python code is running there, or the
// interpreter cannot say.
std::optional<SourceLoc> runningScriptLine();

// What the run is doing, for a message from another thread: "x.py:12:
// /World/Box: ns.on_update() at frame 3" (the line when a script runs),
// "at frame 5" between hooks, "" when nothing is known.
std::string describeRunningCall();

}  // namespace sdg::scripting
