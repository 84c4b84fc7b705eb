#include "behavior/describe.h"

#include <sstream>

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

}  // namespace sdg
