#include "behavior/runtime.h"

#include <stdexcept>

namespace sdg {

BehaviorRuntime::BehaviorRuntime(Stage& stage, const BehaviorRegistry& registry, BehaviorContext context)
    : stage_(stage), registry_(registry), context_(context), timeline_(stage.metadata().timeCodesPerSecond) {
  context_.stage = &stage_;
  context_.events = &events_;
}

BehaviorRuntime::~BehaviorRuntime() {
  // Never throw from a destructor: a failed run has already reported.
  try {
    destroy();
  } catch (...) {
  }
}

void BehaviorRuntime::init() {
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
  for (auto& b : behaviors_) b->onInit();
}

void BehaviorRuntime::play() {
  if (!timeline_.play()) return;
  for (auto& b : behaviors_) b->onPlay();
}

void BehaviorRuntime::pause() {
  if (!timeline_.pause()) return;
  for (auto& b : behaviors_) b->onPause();
}

void BehaviorRuntime::stop() {
  if (!timeline_.stop()) return;
  // Reverse order: a behavior added later restores before those it built on.
  for (auto it = behaviors_.rbegin(); it != behaviors_.rend(); ++it) (*it)->onStop();
}

void BehaviorRuntime::update() {
  ++updates_;
  events_.dispatch();
  double dt = timeline_.advance();
  if (dt <= 0) return;
  for (auto& b : behaviors_) b->onUpdate(timeline_.time(), dt);
}

void BehaviorRuntime::destroy() {
  if (destroyed_) return;
  destroyed_ = true;
  stop();
  for (auto it = behaviors_.rbegin(); it != behaviors_.rend(); ++it) (*it)->onDestroy();
  behaviors_.clear();
}

}  // namespace sdg
