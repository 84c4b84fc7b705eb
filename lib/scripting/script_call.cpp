#include "scripting/script_call.h"

#include "behavior/run_activity.h"
#include "core/diagnostics.h"
#include "scripting/python_host.h"

namespace py = pybind11;

namespace sdg::scripting {

std::string exitCall(py::error_already_set& error) {
  if (error.matches(PyExc_SystemExit)) {
    std::string code = py::repr(error.value().attr("code"));
    return "sys.exit(" + (code == "None" ? std::string() : code) + ")";
  }
  if (error.matches(PythonHost::instance().scriptExitError())) return py::str(error.value());
  return "";
}

void throwScriptCallError(py::error_already_set& error, const std::string& where, const WatchedCall& call) {
  PythonHost::ErrorInfo info = PythonHost::instance().describe(error);
  const std::string at = info.loc.known() ? info.loc.str() + ": " : std::string();
  const std::string when = activity::current().phaseText();
  if (call.timedOut())
    throw RunError(at + where + when + " " + timeoutText() + "; interrupted there:\n" + info.text);
  if (std::string exit = exitCall(error); !exit.empty())
    throw RunError(at + where + when + " called " + exit +
                   ": a script cannot end the run that way; raise an exception to stop it\n" + info.text);
  throw RunError(at + where + " raised:\n" + info.text);
}

void throwCaughtTimeout(const std::string& script, const std::string& where, const WatchedCall& call) {
  std::optional<SourceLoc> line = call.stuckAt();
  throw RunError((line ? line->str() : script) + ": " + where + activity::current().phaseText() + " " + timeoutText() +
                 "; the script caught the interruption (sdgbehave._HookTimeout) and returned");
}

}  // namespace sdg::scripting
