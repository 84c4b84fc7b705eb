#include "behavior/describe.h"

#include <sstream>

#include <nlohmann/json.hpp>

#include "stage/value_json.h"

namespace sdg {

std::string describeBehaviors(const BehaviorRegistry& registry) {
  std::ostringstream out;
  size_t width = 0;
  for (const BehaviorSpec& s : registry.catalog().specs) width = std::max(width, s.name.size());
  for (const BehaviorSpec& s : registry.catalog().specs) {
    out << s.name << std::string(width + 2 - s.name.size(), ' ') << s.summary;
    if (registry.sourceOf(s.name) != "built-in") out << " [" << registry.sourceOf(s.name) << "]";
    out << "\n";
  }
  out << "\nRun `sdgbehave describe NAME` for a behavior's exposed variables.\n";
  return out.str();
}

std::string describeBehavior(const BehaviorRegistry& registry, std::string_view name) {
  const BehaviorSpec* spec = registry.catalog().find(name);
  if (!spec) return {};
  std::ostringstream out;
  out << spec->name << " — " << spec->summary << "\n";
  out << (spec->eventDriven ? "Driven by events.\n" : "Driven by the timeline.\n");
  out << "\nExposed variables (attributes exposedVar:" << spec->name << ":<name>):\n";
  size_t width = 0;
  for (const AttributeSpec& v : spec->variables) width = std::max(width, v.name.size());
  for (const AttributeSpec& v : spec->variables) {
    out << "  " << v.name << std::string(width + 2 - v.name.size(), ' ') << valueTypeName(v.type) << " = "
        << v.defaultValue.toString() << (v.locked ? "  (locked)" : "") << "\n      " << v.doc << "\n";
  }
  if (!spec->events.empty()) {
    out << "\nEvents:\n";
    for (const std::string& e : spec->events) out << "  " << e << "\n";
  }
  if (!spec->example.empty()) out << "\nExample (under a prim's behaviors:):\n  " << spec->example << "\n";
  return out.str();
}

namespace {

const char* fileKindName(FileKind kind) {
  switch (kind) {
    case FileKind::Mesh: return "mesh";
    case FileKind::Image: return "image";
    case FileKind::Any: return "any";
    case FileKind::None: break;
  }
  return nullptr;
}

nlohmann::ordered_json variableJson(const BehaviorSpec& behavior, const AttributeSpec& v) {
  nlohmann::ordered_json j;
  j["name"] = v.name;
  j["attribute"] = exposedAttributeName(behavior.name, v.name);
  j["type"] = std::string(valueTypeName(v.type));
  j["default"] = valueToJson(v.defaultValue);
  j["doc"] = v.doc;
  j["locked"] = v.locked;
  // Bounds: an inclusive minimum for every component, a closed token set,
  // a prim path that must exist, or files of a kind.
  if (v.minimum) j["minimum"] = *v.minimum;
  if (!v.allowedTokens.empty()) j["allowed"] = v.allowedTokens;
  if (v.primPath) j["prim_path"] = true;
  FileKind files = v.files;
  if (files == FileKind::None && (v.type == ValueType::Asset || v.type == ValueType::AssetArray)) files = FileKind::Any;
  if (const char* kind = fileKindName(files)) j["files"] = kind;
  return j;
}

}  // namespace

std::string describeBehaviorsJson(const BehaviorRegistry& registry, std::string_view name) {
  nlohmann::ordered_json behaviors = nlohmann::ordered_json::array();
  for (const BehaviorSpec& s : registry.catalog().specs) {
    if (!name.empty() && s.name != name) continue;
    nlohmann::ordered_json b;
    b["name"] = s.name;
    b["summary"] = s.summary;
    b["source"] = registry.sourceOf(s.name);
    b["driven_by"] = s.eventDriven ? "events" : "timeline";
    b["events"] = s.events;
    b["example"] = s.example;
    nlohmann::ordered_json vars = nlohmann::ordered_json::array();
    for (const AttributeSpec& v : s.variables) vars.push_back(variableJson(s, v));
    b["variables"] = std::move(vars);
    behaviors.push_back(std::move(b));
  }
  if (!name.empty() && behaviors.empty()) return {};
  nlohmann::ordered_json out;
  out["behaviors"] = std::move(behaviors);
  return out.dump(2) + "\n";
}

}  // namespace sdg
