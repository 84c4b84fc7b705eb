// exampleBehavior — a template to copy for a new timeline behavior.
//
// Exposed variables (exposedVar:exampleBehavior:*):
//   interval         uint  0     apply every N updates (0 = every update)
//   includeChildren  bool  true  act on every descendant too
//
// Apply logs one line per prim; replace it with what your behavior does, and
// undo it in restore(). Build it as a shared library against sdgbehave's
// headers and load it with `--plugin libexample_behavior.so` or
// `plugins: [libexample_behavior.so]` in a scene.
//
// Example:
//   behaviors:
//     exampleBehavior: {interval: 2}
//
// Events: none (timeline driven).
#include "behavior/interval_behavior.h"
#include "behavior/plugin_api.h"
#include "core/log.h"

namespace {

class ExampleBehavior final : public sdg::IntervalBehavior {
  void setup() override {
    if (isSetUp()) return;  // caches survive pause/resume; rebuilt after stop
    prims_.clear();
    for (sdg::Prim* p : selectPrims(var<bool>("includeChildren"), [](const sdg::Prim&) { return true; }))
      prims_.push_back(p->path());
  }
  void apply() override {
    for (const std::string& path : prims_) sdg::log::info("exampleBehavior: applied to " + path);
  }
  void restore() override { prims_.clear(); }

  std::vector<std::string> prims_;
};

sdg::BehaviorSpec exampleBehaviorSpec() {
  sdg::BehaviorSpec spec;
  spec.name = "exampleBehavior";
  spec.summary = "Template: logs a line per prim on each apply.";
  auto var = [](std::string name, sdg::Value value, std::string doc) {
    sdg::AttributeSpec s;
    s.name = std::move(name);
    s.type = value.type();
    s.defaultValue = std::move(value);
    s.doc = std::move(doc);
    return s;
  };
  spec.variables = {var("interval", sdg::Value::makeUInt(0), "Apply every N updates; 0 means every update."),
                    var("includeChildren", sdg::Value::makeBool(true), "Also act on every descendant.")};
  spec.example = "exampleBehavior: {interval: 2}";
  return spec;
}

void registerExampleBehavior(sdg::BehaviorRegistry& registry) {
  registry.add(exampleBehaviorSpec(), [] { return std::make_unique<ExampleBehavior>(); });
}

}  // namespace

SDG_BEHAVIOR_PLUGIN(registerExampleBehavior)
