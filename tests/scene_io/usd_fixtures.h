#pragma once
// Test helpers for the USD mapping: compose in-memory usda layers (named by
// virtual paths, so asset paths resolve against them) and a stage with the
// built-in behaviors' catalog.
#include <map>
#include <string>

#include "behavior/registry.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "scene_io/usd_import.h"
#include "usd/compose.h"
#include "usd/layer_io.h"

namespace sdg::test {

inline usd::ComposedStage composeText(const std::map<std::string, std::string>& layers, const std::string& root) {
  return usd::composeStage(root, [&](const std::string& id) {
    auto it = layers.find(id);
    if (it == layers.end()) throw usd::UsdError(SourceLoc{id, 0, 0}, "no such test layer");
    return usd::readUsdaLayer(it->second, id);
  });
}

inline usd::ComposedStage composeText(const std::string& text) { return composeText({{"/v/scene.usda", text}}, "/v/scene.usda"); }

inline const BehaviorCatalog& builtinCatalog() {
  static const BehaviorRegistry registry = [] {
    BehaviorRegistry r;
    registerBuiltinBehaviors(r);
    return r;
  }();
  return registry.catalog();
}

// A usda text imported onto a fresh stage (without a stage's run defaults),
// with the import's problems and report.
struct ImportedStage {
  Stage stage;
  Diagnostics diag;
  UsdImportReport report;
};

inline void importText(const std::string& text, ImportedStage& out) {
  UsdImportOptions options;
  options.runDefaults = false;
  importUsdPrims(composeText(text), "/", out.stage, "/", builtinCatalog(), options, out.report, out.diag);
}

}  // namespace sdg::test
