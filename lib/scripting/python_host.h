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

  // Script files loaded so far (absolute), preferred when a traceback is
  // reduced to one location.
  void addScriptFile(const std::string& absolutePath);

  // Where a Python error happened (a SyntaxError's own place, else the
  // innermost frame in a script) and its text (the formatted traceback).
  struct ErrorInfo {
    SourceLoc loc;
    std::string text;
  };
  ErrorInfo describe(pybind11::error_already_set& error);

  // Seeds `random` (and numpy's global generator) for one iteration.
  void seedGlobalRandom(uint64_t seed);

 private:
  PythonHost();
  // Plain objects: they must stay empty until the interpreter has started.
  pybind11::object api_;
  pybind11::object scriptFiles_;
};

// A Python error during a run: a RunError (exit 1) naming `where` (the prim
// path, behavior and hook) with the script's file:line and traceback.
[[noreturn]] void throwScriptRunError(pybind11::error_already_set& error, const std::string& where);

}  // namespace sdg::scripting
