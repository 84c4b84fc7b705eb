#include "scripting/script_behavior.h"

#include "behavior/rng.h"
#include "scripting/python_host.h"
#include "scripting/script_call.h"

namespace py = pybind11;

namespace sdg::scripting {

ScriptBehavior::ScriptBehavior(py::object behaviorClass, std::string rngStream, std::string script)
    : class_(std::move(behaviorClass)), ctx_(std::make_shared<ScriptContext>()) {
  ctx_->rngStream = std::move(rngStream);
  ctx_->script = std::move(script);
}

ScriptBehavior::~ScriptBehavior() { detach(); }

template <typename... Args>
void ScriptBehavior::call(const py::object& method, const char* hook, Args&&... args) {
  callScript(
      ctx_->script, [&] { return primPath() + ": " + spec().name + "." + hook + "()"; },
      [&] { method(std::forward<Args>(args)...); });
}

void ScriptBehavior::onInit() {
  ScriptContext& c = *ctx_;
  c.stage = &stage();
  c.events = &events();
  c.assets = context().assets;
  c.spec = &spec();
  c.primPath = primPath();
  c.runSeed = context().runSeed;
  c.iteration = context().iteration;
  // `random` and numpy's global generator, for scripts that use them anyway:
  // the same seed for every behavior of an iteration keeps runs reproducible.
  PythonHost::instance().seedGlobalRandom(mix64(uint64_t(c.runSeed) ^ mix64(c.iteration + 0x5d)));
  callScript(
      ctx_->script, [&] { return primPath() + ": " + spec().name + ".__init__()"; },
      [&] {
        instance_ = class_();
        instance_.attr("_ctx") = py::cast(ctx_);
        onUpdate_ = instance_.attr("on_update");
      });
  call(instance_.attr("on_init"), "on_init");
}

void ScriptBehavior::onPlay() {
  ctx_->playing = true;
  call(instance_.attr("on_play"), "on_play");
}

void ScriptBehavior::onUpdate(double time, double dt) { call(onUpdate_, "on_update", time, dt); }

void ScriptBehavior::onPause() { call(instance_.attr("on_pause"), "on_pause"); }

void ScriptBehavior::onStop() {
  call(instance_.attr("on_stop"), "on_stop");
  ctx_->playJournal.undo(stage());
  ctx_->playing = false;
  ctx_->rngReady = false;  // the next play replays the stream from its start
}

void ScriptBehavior::onDestroy() {
  if (destroyed_) return;
  destroyed_ = true;
  if (instance_) call(instance_.attr("on_destroy"), "on_destroy");
  for (EventBus::Subscription id : ctx_->subscriptions) events().unsubscribe(id);
  ctx_->subscriptions.clear();
  ctx_->playJournal.undo(stage());
  ctx_->idleJournal.undo(stage());
  detach();
}

void ScriptBehavior::detach() {
  // Handles a script kept (a global list, a closure) now raise instead of
  // reaching a stage that is gone.
  ctx_->stage = nullptr;
  ctx_->events = nullptr;
  if (instance_) {
    try {
      instance_.attr("_ctx") = py::none();
    } catch (py::error_already_set&) {
    }
  }
  onUpdate_ = py::object();
  instance_ = py::object();
}

}  // namespace sdg::scripting
