#include "behavior/runtime.h"

#include <stdexcept>

#include "core/log.h"

namespace sdg {
namespace {

// A behavior's hook, recorded while it runs.
template <typename Call>
void callHook(Behavior& b, const char* hook, Call&& call) {
  activity::HookScope scope(b.primPath(), b.spec().name, hook);
  call();
}

}  // namespace

BehaviorRuntime::BehaviorRuntime(Stage& stage, const BehaviorRegistry& registry, BehaviorContext context)
    : stage_(stage),
      registry_(registry),
      context_(context),
      timeline_(stage.metadata().timeCodesPerSecond),
      animation_(stage) {
  context_.stage = &stage_;
  context_.events = &events_;
}

BehaviorRuntime::~BehaviorRuntime() {
  // Never throw from a destructor: a failed run has already reported.
  try {
    destroy();
  } catch (...) {
  }
  activity::setPhase(activity::Phase::Idle);
}

void BehaviorRuntime::notePhase(activity::Phase phase, uint64_t step) const {
  const uint64_t frame = context_.firstFrame.value_or(0) + step;
  std::optional<uint64_t> iteration;
  if (!context_.firstFrame && context_.iteration > 0) iteration = context_.iteration;
  activity::setPhase(phase, frame, iteration);
}

void BehaviorRuntime::init() {
  activity::setPhase(activity::Phase::Init);
  std::vector<std::pair<Prim*, std::string>> attached;
  stage_.traverse([&](Prim& prim) {
    for (const std::string& name : prim.behaviors()) attached.emplace_back(&prim, name);
  });
  for (auto& [prim, name] : attached) {
    const BehaviorSpec* spec = registry_.catalog().find(name);
    std::unique_ptr<Behavior> behavior = registry_.create(name);
    if (!spec || !behavior) throw std::logic_error("behavior " + name + " is not registered");
    createExposedVariables(*prim, *spec);
    behavior->bind(*prim, *spec, context_);
    behaviors_.push_back(std::move(behavior));
  }
  for (auto& b : behaviors_) callHook(*b, "on_init", [&] { b->onInit(); });
}

void BehaviorRuntime::attach(Prim& prim, const std::string& name) {
  const BehaviorSpec* spec = registry_.catalog().find(name);
  std::unique_ptr<Behavior> behavior = registry_.create(name);
  if (!spec || !behavior) throw std::logic_error("behavior " + name + " is not registered");
  createExposedVariables(prim, *spec);
  behavior->bind(prim, *spec, context_);
  Behavior& b = *behavior;
  behaviors_.push_back(std::move(behavior));
  callHook(b, "on_init", [&] { b.onInit(); });
  if (timeline_.playing()) callHook(b, "on_play", [&] { b.onPlay(); });
}

void BehaviorRuntime::play() {
  if (!timeline_.play()) return;
  notePhase(activity::Phase::Frame, timeline_.steps());
  animation_.play();
  for (auto& b : behaviors_) callHook(*b, "on_play", [&] { b->onPlay(); });
}

void BehaviorRuntime::pause() {
  if (!timeline_.pause()) return;
  for (auto& b : behaviors_) callHook(*b, "on_pause", [&] { b->onPause(); });
}

void BehaviorRuntime::stop() {
  if (timeline_.state() == Timeline::State::Stopped) return;
  // The events of the last update would otherwise never arrive.
  notePhase(activity::Phase::AfterFrames, timeline_.steps() ? timeline_.steps() - 1 : 0);
  events_.dispatch();
  stopHooks();
}

void BehaviorRuntime::stopHooks() {
  if (timeline_.state() == Timeline::State::Stopped) return;
  notePhase(activity::Phase::AfterFrames, timeline_.steps() ? timeline_.steps() - 1 : 0);
  timeline_.stop();
  // Reverse order: a behavior added later restores before those it built on.
  for (auto it = behaviors_.rbegin(); it != behaviors_.rend(); ++it)
    callHook(**it, "on_stop", [&] { (*it)->onStop(); });
  animation_.stop();  // the samples were under every behavior: put back last
}

void BehaviorRuntime::update() {
  ++updates_;
  if (timeline_.playing()) notePhase(activity::Phase::Frame, timeline_.steps());
  else activity::setPhase(activity::Phase::Preroll, ++prerollUpdates_);
  events_.dispatch();
  double dt = timeline_.advance();
  if (dt <= 0) return;
  animation_.update(timeline_.steps(), timeline_.rate());
  for (auto& b : behaviors_) callHook(*b, "on_update", [&] { b->onUpdate(timeline_.time(), dt); });
}

void BehaviorRuntime::destroy() {
  if (destroyed_) return;
  destroyed_ = true;
  stopHooks();
  if (events_.pending())
    log::debug(std::to_string(events_.pending()) + " event(s) published after the last delivery (while stopping or "
                                                   "destroying) were not delivered");
  for (auto it = behaviors_.rbegin(); it != behaviors_.rend(); ++it)
    callHook(**it, "on_destroy", [&] { (*it)->onDestroy(); });
  behaviors_.clear();
}

}  // namespace sdg
