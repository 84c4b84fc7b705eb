#pragma once
// What the behaviors of the run are doing right now, readable from any
// thread: the hook watchdog and the stop-signal handler name the prim, the
// behavior, the hook and the frame a stuck or interrupted run was in.
// BehaviorRuntime keeps it up to date around every hook; scripting adds the
// event callbacks of scripts and the loading of a script.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace sdg::activity {

// Where the runtime is in the run: `number` is the pre-roll update (from 1)
// or the frame. Frames are the dataset's frame numbers, or, with
// `iteration`, frame numbers within that iteration (when the run did not
// say where the iteration starts).
enum class Phase { Idle, Init, Preroll, Frame, AfterFrames };
void setPhase(Phase phase, uint64_t number = 0, std::optional<uint64_t> iteration = std::nullopt);

struct Snapshot;

// A hook in progress, from construction to destruction (an inner scope
// hides the outer one until it ends). The strings must outlive the scope:
// nothing is copied on the hot path, only when someone reads.
class HookScope {
 public:
  enum class Kind {
    Method,    // "<subject>: <behavior>.<hook>()"
    Callback,  // "<subject>: <behavior>: <hook>" (hook: "the callback for event 'x'")
    Loading,   // "loading the script <subject>"
  };
  HookScope(std::string_view subject, std::string_view behavior, std::string_view hook, Kind kind = Kind::Method);
  ~HookScope();
  HookScope(const HookScope&) = delete;
  HookScope& operator=(const HookScope&) = delete;

 private:
  friend Snapshot current();
  std::string_view subject_, behavior_, hook_;
  Kind kind_;
  const HookScope* saved_;
};

struct Snapshot {
  bool inHook = false;
  HookScope::Kind kind = HookScope::Kind::Method;
  std::string subject, behavior, hook;
  Phase phase = Phase::Idle;
  uint64_t number = 0;
  std::optional<uint64_t> iteration;

  // "/World/Box: hang.on_update() at frame 3", "in pre-roll update 2",
  // "loading the script s.py"; "" when nothing is known.
  std::string text() const;
  // " at frame 3", " in pre-roll update 2", " before the pre-roll",
  // " after frame 5" or "".
  std::string phaseText() const;
};
Snapshot current();

}  // namespace sdg::activity
