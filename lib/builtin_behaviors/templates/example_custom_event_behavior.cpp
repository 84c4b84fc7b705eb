// exampleCustomEventBehavior — a template for an event-driven behavior.
//
// Exposed variables (exposedVar:exampleCustomEventBehavior:*):
//   includeChildren  bool    true
//   event:input      string  "exampleCustomEventBehavior.in"   locked: the subscription is made at init
//   event:output     string  "exampleCustomEventBehavior.out"  the reply event
//
// It listens on the input event. A payload whose prim_path is empty or this
// prim's path and whose function_name is setup, update or reset runs that
// function, which then publishes {prim_path, function_name} on the output
// event. It uses no timeline hooks. Drive it from a scene's pre-roll:
//
//   events:
//     - {publish: exampleCustomEventBehavior.in, payload: {function_name: setup},
//        wait_for: {function_name: setup}, max_updates: 5}
#include "behavior/plugin_api.h"
#include "core/log.h"

namespace {

constexpr const char* kInput = "exampleCustomEventBehavior.in";
constexpr const char* kOutput = "exampleCustomEventBehavior.out";

class ExampleCustomEventBehavior final : public sdg::Behavior {
 public:
  void onInit() override {
    subscription_ = events().subscribe(kInput, [this](const sdg::Payload& payload) { onEvent(payload); });
  }
  void onDestroy() override {
    if (subscription_) events().unsubscribe(subscription_);
    subscription_ = 0;
  }

 private:
  void onEvent(const sdg::Payload& payload) {
    if (!addressedToMe(payload)) return;
    std::string_view function = payload.getString("function_name");
    if (function == "setup") {
      output_ = var<std::string>("event:output");
      prims_.clear();
      for (sdg::Prim* p : selectPrims(var<bool>("includeChildren"), [](const sdg::Prim&) { return true; }))
        prims_.push_back(p->path());
    } else if (function == "update") {
      for (const std::string& path : prims_) sdg::log::info("exampleCustomEventBehavior: update " + path);
    } else if (function == "reset") {
      prims_.clear();
    } else {
      return;
    }
    events().publish(output_.empty() ? kOutput : output_,
                     sdg::Payload{{"prim_path", primPath()}, {"function_name", std::string(function)}});
  }

  sdg::EventBus::Subscription subscription_ = 0;
  std::string output_;
  std::vector<std::string> prims_;
};

void registerExampleCustomEventBehavior(sdg::BehaviorRegistry& registry) {
  auto var = [](std::string name, sdg::Value value, std::string doc, bool locked = false) {
    sdg::AttributeSpec s;
    s.name = std::move(name);
    s.type = value.type();
    s.defaultValue = std::move(value);
    s.doc = std::move(doc);
    s.locked = locked;
    return s;
  };
  sdg::BehaviorSpec spec;
  spec.name = "exampleCustomEventBehavior";
  spec.summary = "Template: answers setup/update/reset events with a reply event.";
  spec.eventDriven = true;
  spec.variables = {var("includeChildren", sdg::Value::makeBool(true), "Also act on every descendant."),
                    var("event:input", sdg::Value::makeString(kInput), "Event it listens on (informational).", true),
                    var("event:output", sdg::Value::makeString(kOutput), "Event it replies on.")};
  spec.events = {std::string(kInput) + " (in): {function_name: setup|update|reset, prim_path?}",
                 std::string(kOutput) + " (out): {prim_path, function_name}"};
  registry.add(std::move(spec), [] { return std::make_unique<ExampleCustomEventBehavior>(); });
}

}  // namespace

SDG_BEHAVIOR_PLUGIN(registerExampleCustomEventBehavior)
