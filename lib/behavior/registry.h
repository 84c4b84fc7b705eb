#pragma once
// Behavior names -> specs and factories. Built-ins are added from one table
// (builtin_behaviors/builtin_behaviors.cpp); plugins add theirs through the same
// add() from a versioned C entry point (plugin_api.h).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "behavior/behavior.h"
#include "core/source_loc.h"
#include "stage/behavior_spec.h"

namespace sdg {

using BehaviorFactory = std::function<std::unique_ptr<Behavior>()>;

class BehaviorRegistry {
 public:
  // A second behavior of the same name is an error naming both sources.
  void add(BehaviorSpec spec, BehaviorFactory factory, std::string source = "built-in");
  // An Isaac Sim script whose namespace is a built-in's (locationRandomizer,
  // ...) takes the built-in's place in this registry; otherwise as add().
  void replaceBuiltin(BehaviorSpec spec, BehaviorFactory factory, std::string source);
  const BehaviorCatalog& catalog() const { return catalog_; }
  // A file prims list in omni:scripting:scripts stands for `behaviors`.
  void attachScriptFile(const std::string& path, std::vector<std::string> behaviors) {
    catalog_.attachedScripts[path] = std::move(behaviors);
  }
  std::unique_ptr<Behavior> create(std::string_view name) const;
  const std::string& sourceOf(std::string_view name) const;

  // Loads a plugin library; problems (missing file, not a plugin, wrong ABI
  // version, duplicate names) throw SceneError located at `where`.
  void loadPlugin(const std::string& path, const SourceLoc& where);

 private:
  // Declared first so it is destroyed last: factories and specs hold code
  // that lives in the plugin libraries.
  std::vector<std::shared_ptr<void>> libraries_;
  BehaviorCatalog catalog_;
  std::vector<BehaviorFactory> factories_;  // index-aligned with catalog_.specs
  std::vector<std::string> sources_;
};

// A registry holding the built-in behaviors.
BehaviorRegistry builtinRegistry();

}  // namespace sdg
