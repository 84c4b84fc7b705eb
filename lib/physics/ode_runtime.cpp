#include "physics/ode_runtime.h"

#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>

#include <ode/ode.h>

#include "core/log.h"

namespace sdg::ode {
namespace {

std::string format(int errnum, const char* msg, va_list ap) {
  char buffer[1024];
  std::vsnprintf(buffer, sizeof buffer, msg, ap);
  return "ODE " + std::to_string(errnum) + ": " + buffer;
}

// ODE calls its error handler for broken invariants and then expects no
// return; a log line is all we can add before the abort it performs.
void onError(int errnum, const char* msg, va_list ap) {
  log::error(format(errnum, msg, ap));
  std::abort();
}
void onDebug(int errnum, const char* msg, va_list ap) {
  log::error(format(errnum, msg, ap));
  std::abort();
}
void onMessage(int errnum, const char* msg, va_list ap) { log::debug(format(errnum, msg, ap)); }

}  // namespace

void ensureInitialized() {
  static std::once_flag once;
  std::call_once(once, [] {
    dSetErrorHandler(onError);
    dSetDebugHandler(onDebug);
    dSetMessageHandler(onMessage);
    dInitODE2(0);
    dAllocateODEDataForThread(dAllocateMaskAll);
    std::atexit([] { dCloseODE(); });
  });
}

void resetRandomSeed() { dRandSetSeed(0); }

}  // namespace sdg::ode
