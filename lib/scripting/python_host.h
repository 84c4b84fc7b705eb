#pragma once
// The embedded CPython interpreter. It starts on the first script a scene
// uses, so commands on scenes without scripts never pay for it, and lives
// until the process exits (it is never finalized: script objects may be
// released at any time before). It runs isolated from the user's Python
// environment (no PYTHON* variables, no user site, the working directory
// not on sys.path), with the string hash seed fixed at 0 so that set and
// dict iteration orders are the same in every run, unbuffered, and with
// print() going to stderr (stdout carries sdgbehave's own results).
//
// Every call into Python happens on the thread that started it (the run's
// main thread), which holds the interpreter lock throughout.
#include <pthread.h>

#include <string>

#include <pybind11/pybind11.h>

#include "core/source_loc.h"

namespace sdg::scripting {

class PythonHost {
 public:
  // The host, started on first use.
  static PythonHost& instance();
  static bool started();

  // The `sdgbehave` module (the pure-Python half, sdgbehave.py).
  pybind11::object& api() { return api_; }

  // A script file loaded: its absolute path (what Python's frames name) and
  // the path it was given as (relative to the working folder, or absolute),
  // which every message shows. Script frames are preferred when a traceback
  // is reduced to one location.
  void addScriptFile(const std::string& absolutePath, const std::string& shownPath);

  // Where a Python error happened (a SyntaxError's own place, else the
  // innermost frame in a script) and its text (the formatted traceback).
  struct ErrorInfo {
    SourceLoc loc;
    std::string text;
  };
  ErrorInfo describe(pybind11::error_already_set& error);

  // Seeds `random` (and numpy's global generator) for one iteration.
  void seedGlobalRandom(uint64_t seed);

  // The exception os._exit raises in a script (sdgbehave.ScriptExit).
  pybind11::handle scriptExitError() const { return scriptExit_; }

 private:
  PythonHost();
  // Plain objects: they must stay empty until the interpreter has started.
  pybind11::object api_;
  pybind11::object scriptFiles_;  // a dict: absolute path -> shown path
  pybind11::object scriptExit_;
};

// The Python state of the thread that started the interpreter and runs
// every script, for reading its stack from other threads; null until the
// interpreter is ready. Any thread.
PyThreadState* scriptThreadState();
// That thread, for signals aimed at it.
pthread_t scriptThread();

// The path a script was given as, for a path its frames name (absolute);
// `path` itself when it is no loaded script. Any thread, no interpreter lock.
std::string shownScriptPath(const std::string& path);
// Whether `path` (absolute, as frames name it) is a loaded script. Any thread.
bool isScriptPath(const std::string& path);

}  // namespace sdg::scripting
