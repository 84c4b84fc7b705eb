#pragma once
// The state one scripted behavior instance shares with its Python object
// (`self._ctx`): where it lives on the stage, its random stream, its
// subscriptions and the journals of what it changed. Owned jointly by the
// ScriptBehavior and Python; detached (stage == nullptr) when the behavior
// is destroyed, after which every call from Python raises.
#include <string>
#include <vector>

#include "behavior/event_bus.h"
#include "behavior/rng.h"
#include "scripting/stage_journal.h"
#include "stage/behavior_spec.h"
#include "stage/stage.h"

namespace sdg {
class AssetResolver;
}

namespace sdg::scripting {

struct ScriptContext {
  Stage* stage = nullptr;
  EventBus* events = nullptr;
  const AssetResolver* assets = nullptr;  // the scene's search roots
  const BehaviorSpec* spec = nullptr;
  std::string primPath;
  std::string script;     // the file of the behavior's class, as shown in messages
  std::string rngStream;  // RNG_STREAM, else BEHAVIOR_NS
  int64_t runSeed = 0;
  uint64_t iteration = 0;

  // Created on first use after init or a stop (so a fixed seed replays).
  Rng rng;
  bool rngReady = false;

  // Changes made while the timeline plays are undone on stop; changes made
  // otherwise (on_init, pre-roll events) are undone on destroy.
  StageJournal playJournal;
  StageJournal idleJournal;
  bool playing = false;

  std::vector<EventBus::Subscription> subscriptions;

  // The context of a driver program (`sdgbehave exec`), not of a behavior:
  // it edits the stage as its author (prims anywhere, nothing journaled or
  // undone on stop).
  bool driver = false;

  StageJournal& journal() { return playing ? playJournal : idleJournal; }
  // Both journals know a prim as created by this behavior.
  bool created(const Prim& prim) const {
    return driver || playJournal.createdHere(prim) || idleJournal.createdHere(prim);
  }
  const std::string& ns() const { return spec->name; }
  // The stage, or a RuntimeError for Python once detached.
  Stage& liveStage() const;
  Rng& randomStream();
};

}  // namespace sdg::scripting
