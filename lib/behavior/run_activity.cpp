#include "behavior/run_activity.h"

#include <mutex>

namespace sdg::activity {
namespace {

// Written by the run's main thread, read by the watchdog and the signal
// thread: a mutex, held for a few stores or one copy.
std::mutex gMutex;
const HookScope* gHook = nullptr;
Phase gPhase = Phase::Idle;
uint64_t gNumber = 0;
std::optional<uint64_t> gIteration;

}  // namespace

void setPhase(Phase phase, uint64_t number, std::optional<uint64_t> iteration) {
  std::lock_guard lock(gMutex);
  gPhase = phase;
  gNumber = number;
  gIteration = iteration;
}

HookScope::HookScope(std::string_view subject, std::string_view behavior, std::string_view hook, Kind kind)
    : subject_(subject), behavior_(behavior), hook_(hook), kind_(kind) {
  std::lock_guard lock(gMutex);
  saved_ = gHook;
  gHook = this;
}

HookScope::~HookScope() {
  std::lock_guard lock(gMutex);
  gHook = saved_;
}

Snapshot current() {
  std::lock_guard lock(gMutex);
  Snapshot s;
  s.phase = gPhase;
  s.number = gNumber;
  s.iteration = gIteration;
  if (gHook) {
    s.inHook = true;
    s.kind = gHook->kind_;
    s.subject = gHook->subject_;
    s.behavior = gHook->behavior_;
    s.hook = gHook->hook_;
  }
  return s;
}

std::string Snapshot::phaseText() const {
  const std::string ofIteration = iteration ? " of iteration " + std::to_string(*iteration) : "";
  switch (phase) {
    case Phase::Idle: return "";
    case Phase::Init: return " before the pre-roll";
    case Phase::Preroll: return " in pre-roll update " + std::to_string(number);
    case Phase::Frame: return " at frame " + std::to_string(number) + ofIteration;
    case Phase::AfterFrames: return " after frame " + std::to_string(number) + ofIteration;
  }
  return "";
}

std::string Snapshot::text() const {
  if (!inHook) return phaseText().empty() ? std::string() : phaseText().substr(1);
  switch (kind) {
    case HookScope::Kind::Method: return subject + ": " + behavior + "." + hook + "()" + phaseText();
    case HookScope::Kind::Callback: return subject + ": " + behavior + ": " + hook + phaseText();
    case HookScope::Kind::Loading: return "loading the script " + subject;
  }
  return "";
}

}  // namespace sdg::activity
