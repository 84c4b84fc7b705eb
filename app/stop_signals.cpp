#include "stop_signals.h"

#include <fcntl.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <string>
#include <thread>

#include "core/log.h"
#include "scripting/script_stack.h"

namespace sdg::cli {
namespace {

int gPipe[2] = {-1, -1};

// Async-signal-safe: only write(2). The thread below does the rest.
void onStopSignal(int signal) {
  const unsigned char byte = static_cast<unsigned char>(signal);
  [[maybe_unused]] ssize_t n = write(gPipe[1], &byte, 1);
}

// Reads the first signal, reports where the run was and exits. Reading the
// script line needs no interpreter lock, so a script stuck in a loop (or in
// C code holding the lock) cannot keep this thread from exiting.
void reportAndExit() {
  unsigned char byte = 0;
  while (read(gPipe[0], &byte, 1) != 1) {
  }
  const int signal = byte;
  const char* name = signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "a signal";
  const std::string where = scripting::describeRunningCall();
  log::error((where.empty() ? std::string() : where + ": ") + "stopped by " + name + " (exit " +
             std::to_string(128 + signal) + ")");
  _exit(128 + signal);
}

}  // namespace

void installStopSignalHandlers() {
  if (pipe2(gPipe, O_CLOEXEC) != 0) return;  // the default actions stay: the run still stops
  std::thread(reportAndExit).detach();
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = &onStopSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

}  // namespace sdg::cli
