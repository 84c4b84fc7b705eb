#pragma once
// Plain description of a behavior: its namespace, its exposed variables and
// documentation. The behavior registry produces these; the loader, the YAML
// writer, `describe` and the JSON Schema all read them (one source of truth).
#include <deque>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostics.h"
#include "stage/prim.h"

namespace sdg {

inline constexpr std::string_view kExposedAttrNamespace = "exposedVar";

struct BehaviorSpec {
  std::string name;  // the namespace, e.g. "locationRandomizer"
  std::string summary;
  std::vector<AttributeSpec> variables;
  std::string example;  // a short YAML example for docs
  std::vector<std::string> events;  // events it publishes or consumes
  bool eventDriven = false;
  // Checks across variables (e.g. min <= max), run by the loader with the
  // prim's final values; reports at the attributes' locations.
  std::function<void(const Prim&, Diagnostics&)> validate;

  const AttributeSpec* findVariable(std::string_view variable) const;
  std::vector<std::string> variableNames() const;
};

struct BehaviorCatalog {
  // A deque: behaviors bound to a spec keep its address while scripts
  // loaded later add theirs (sdgbehave exec attaches scripts as it runs).
  std::deque<BehaviorSpec> specs;
  // Script files prims list in omni:scripting:scripts (absolute) -> the
  // behaviors each stands for (its classes, or the built-in standing in).
  std::map<std::string, std::vector<std::string>> attachedScripts;
  const BehaviorSpec* find(std::string_view name) const;
  std::vector<std::string> names() const;
};

// "exposedVar:<behavior>:<variable>"
std::string exposedAttributeName(std::string_view behavior, std::string_view variable);
// Creates every exposed variable of `spec` on `prim` that is not there yet,
// with its default; values already authored are kept.
void createExposedVariables(Prim& prim, const BehaviorSpec& spec);
// Removes the exposed variables of `spec` from `prim`.
void removeExposedVariables(Prim& prim, const BehaviorSpec& spec);

}  // namespace sdg
