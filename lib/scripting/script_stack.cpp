#include "scripting/script_stack.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <unistd.h>

#include <regex>
#include <sstream>
#include <string>

#include <Python.h>

#include "behavior/run_activity.h"
#include "scripting/python_host.h"

namespace sdg::scripting {
namespace {

// CPython's own stack dumper (what faulthandler calls): it reads another
// thread's frames without the interpreter lock and writes them to a file
// descriptor with write(2) only. Private API, so looked up at run time: an
// interpreter without it only costs the line number.
using DumpTraceback = void (*)(int fd, PyThreadState* thread);

DumpTraceback dumper() {
  static const auto fn = reinterpret_cast<DumpTraceback>(dlsym(RTLD_DEFAULT, "_Py_DumpTraceback"));
  return fn;
}

// The dump: `  File "/abs/x.py", line 12 in apply`, innermost frame first.
std::string dumpStack(PyThreadState* thread) {
  int fds[2];
  // Non-blocking: a stack deeper than the pipe holds is cut, never waited on.
  if (pipe2(fds, O_NONBLOCK | O_CLOEXEC) != 0) return {};
  dumper()(fds[1], thread);
  close(fds[1]);
  std::string text;
  char buffer[4096];
  for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) > 0;) text.append(buffer, size_t(n));
  close(fds[0]);
  return text;
}

}  // namespace

std::optional<SourceLoc> runningScriptLine() {
  PyThreadState* thread = scriptThreadState();
  if (!thread || !dumper()) return std::nullopt;
  static const std::regex frameLine(R"re(^\s*File "(.*)", line (\d+) in .*$)re");
  std::istringstream lines(dumpStack(thread));
  std::optional<SourceLoc> innermost;
  for (std::string line; std::getline(lines, line);) {
    std::smatch m;
    if (!std::regex_match(line, m, frameLine)) continue;
    SourceLoc loc{shownScriptPath(m[1].str()), std::stoi(m[2].str()), 0};
    if (isScriptPath(m[1].str())) return loc;
    if (!innermost) innermost = loc;
  }
  return innermost;
}

std::string describeRunningCall() {
  const std::string what = activity::current().text();
  std::optional<SourceLoc> line = runningScriptLine();
  if (!line) return what;
  return line->str() + ": " + (what.empty() ? std::string("a script") : what);
}

}  // namespace sdg::scripting
