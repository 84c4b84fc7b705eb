#pragma once
// The base class of every behavior: lifecycle hooks the runtime calls, and
// helpers to read exposed variables, make random streams and select prims.
// A behavior writes only its own prims' attributes and ops (and prims it
// creates under /Behaviors); it never renders and never sees writers.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "behavior/event_bus.h"
#include "behavior/rng.h"
#include "stage/behavior_spec.h"
#include "stage/stage.h"

namespace sdg {

class AssetResolver;
struct PhysicsSettings;

// Hooks the run layer may install. Behaviors call them and never learn who
// listens, so data still flows one way: behaviors -> renderer / summary.
struct RunHooks {
  // A physics step moved prims (renderSimulation): render this state.
  std::function<void(const Stage& stage, const std::string& owner, uint64_t step)> simulationFrame;
  // A measurement for the run summary and the record, e.g. settle quality.
  std::function<void(const std::string& behavior, const nlohmann::ordered_json& report)> report;
};

// What a behavior may use while the scene runs.
struct BehaviorContext {
  Stage* stage = nullptr;
  EventBus* events = nullptr;
  const AssetResolver* assets = nullptr;
  const PhysicsSettings* physics = nullptr;  // null: the defaults
  RunHooks hooks;
  int64_t runSeed = 0;
  uint64_t iteration = 0;
  // The dataset frame number of the iteration's first frame, for messages
  // that name a frame (unset: frames are counted within the iteration).
  std::optional<uint64_t> firstFrame;
};

class Behavior {
 public:
  virtual ~Behavior() = default;
  Behavior() = default;
  Behavior(const Behavior&) = delete;
  Behavior& operator=(const Behavior&) = delete;

  // Called once by the runtime before onInit.
  void bind(Prim& prim, const BehaviorSpec& spec, BehaviorContext& context);

  virtual void onInit() {}
  virtual void onPlay() {}
  virtual void onUpdate(double time, double dt) { (void)time, (void)dt; }
  virtual void onPause() {}
  virtual void onStop() {}
  virtual void onDestroy() {}

  const std::string& primPath() const { return primPath_; }
  const BehaviorSpec& spec() const { return *spec_; }

 protected:
  Prim& prim() const;
  Stage& stage() const { return *context_->stage; }
  EventBus& events() const { return *context_->events; }
  const BehaviorContext& context() const { return *context_; }

  // The current value of exposed variable `name` (its attribute on the prim).
  const Value& variable(std::string_view name) const;
  template <typename T>
  const T& var(std::string_view name) const { return variable(name).get<T>(); }
  std::string attributeName(std::string_view variable) const;

  // This (behavior, prim)'s random stream; `fixedSeed` >= 0 fixes it.
  Rng makeRng(int32_t fixedSeed) const;

  // The prim itself (and with includeChildren its descendants, pre-order)
  // that satisfy `accept`.
  std::vector<Prim*> selectPrims(bool includeChildren, const std::function<bool(const Prim&)>& accept) const;
  // The path in string variable `name` when it names an Xformable prim;
  // otherwise "" after a warning with the path and what happens instead.
  std::string xformableTarget(std::string_view name, std::string_view fallbackNote) const;
  // True when the payload has no prim_path, an empty one, or this prim's.
  bool addressedToMe(const Payload& payload) const;

 private:
  std::string primPath_;  // looked up again on use: behaviors may remove prims
  const BehaviorSpec* spec_ = nullptr;
  BehaviorContext* context_ = nullptr;
};

}  // namespace sdg
