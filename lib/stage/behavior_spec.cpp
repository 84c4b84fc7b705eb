#include "stage/behavior_spec.h"

namespace sdg {

const AttributeSpec* BehaviorSpec::findVariable(std::string_view variable) const {
  for (const AttributeSpec& v : variables)
    if (v.name == variable) return &v;
  return nullptr;
}

std::vector<std::string> BehaviorSpec::variableNames() const {
  std::vector<std::string> names;
  for (const AttributeSpec& v : variables) names.push_back(v.name);
  return names;
}

const BehaviorSpec* BehaviorCatalog::find(std::string_view name) const {
  for (const BehaviorSpec& s : specs)
    if (s.name == name) return &s;
  return nullptr;
}

std::vector<std::string> BehaviorCatalog::names() const {
  std::vector<std::string> names;
  for (const BehaviorSpec& s : specs) names.push_back(s.name);
  return names;
}

std::string exposedAttributeName(std::string_view behavior, std::string_view variable) {
  std::string name(kExposedAttrNamespace);
  name += ':';
  name += behavior;
  name += ':';
  name += variable;
  return name;
}

void createExposedVariables(Prim& prim, const BehaviorSpec& spec) {
  for (const AttributeSpec& v : spec.variables) {
    std::string name = exposedAttributeName(spec.name, v.name);
    if (prim.findAttribute(name)) continue;
    Attribute& a = prim.setAttribute(name, v.defaultValue, true);
    a.doc = v.doc;
  }
}

void removeExposedVariables(Prim& prim, const BehaviorSpec& spec) {
  for (const AttributeSpec& v : spec.variables) prim.removeAttribute(exposedAttributeName(spec.name, v.name));
}

}  // namespace sdg
