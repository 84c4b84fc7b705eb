// exampleBaseBehavior — a template subclass of BaseBehavior (base_behavior.h).
//
// Exposed variables (exposedVar:exampleBaseBehavior:*):
//   interval         uint  0     from BaseBehavior
//   includeChildren  bool  true  act on every descendant too
//
// Apply logs one line per prim. Example:
//   behaviors:
//     exampleBaseBehavior: {interval: 3}
//
// Events: none (timeline driven).
#include "base_behavior.h"
#include "behavior/plugin_api.h"
#include "core/log.h"

namespace {

class ExampleBaseBehavior final : public templates::BaseBehavior {
 public:
  void onPlay() override {
    BaseBehavior::onPlay();
    prims_.clear();
    for (sdg::Prim* p : selectPrims(var<bool>("includeChildren"), [](const sdg::Prim&) { return true; }))
      prims_.push_back(p->path());
  }
  void onStop() override {
    BaseBehavior::onStop();
    prims_.clear();
  }

 protected:
  void apply() override {
    for (const std::string& path : prims_) sdg::log::info("exampleBaseBehavior: applied to " + path);
  }

 private:
  std::vector<std::string> prims_;
};

void registerExampleBaseBehavior(sdg::BehaviorRegistry& registry) {
  sdg::BehaviorSpec spec;
  spec.name = "exampleBaseBehavior";
  spec.summary = "Template: a BaseBehavior subclass that logs a line per prim.";
  spec.variables = templates::BaseBehavior::baseVariables();
  sdg::AttributeSpec includeChildren;
  includeChildren.name = "includeChildren";
  includeChildren.type = sdg::ValueType::Bool;
  includeChildren.defaultValue = sdg::Value::makeBool(true);
  includeChildren.doc = "Also act on every descendant.";
  spec.variables.push_back(includeChildren);
  spec.example = "exampleBaseBehavior: {interval: 3}";
  registry.add(std::move(spec), [] { return std::make_unique<ExampleBaseBehavior>(); });
}

}  // namespace

SDG_BEHAVIOR_PLUGIN(registerExampleBaseBehavior)
