#include "scene_io/usd_settings.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/text.h"
#include "scene_io/map_reader.h"
#include "scene_io/scene_loader.h"
#include "scene_io/usd_value_node.h"

namespace sdg {
namespace {

using usd::Kind;

// Whole numbers without a decimal point: a list of numbers is written as
// doubles whatever the option's type, and an integer option reads "512",
// not "512.0"; a floating-point option reads either the same.
std::string numberText(Kind kind, double x) {
  if (kind == Kind::Bool) return x != 0 ? "true" : "false";
  if (std::isfinite(x) && x == std::trunc(x) && std::fabs(x) < 9007199254740992.0)
    return std::to_string(static_cast<long long>(x));
  return text::formatDouble(x);
}

// A customLayerData value as the node the YAML reader would have built:
// dictionaries as mappings, numbers and bools as plain scalars, text as
// quoted scalars, arrays (and vectors) as sequences.
RawNode toNode(const usd::Value& v, const SourceLoc& loc) {
  RawNode n;
  n.loc = loc;
  if (v.kind == Kind::Dictionary && v.dictionary) {
    n.kind = RawNode::Kind::Map;
    for (const auto& [key, value] : *v.dictionary) n.entries.push_back({scalarNode(key, true, loc), toNode(value, loc)});
    return n;
  }
  if (usd::isText(v.kind)) {
    if (!v.isArray) return scalarNode(v.strings.empty() ? "" : v.strings[0], true, loc);
    n.kind = RawNode::Kind::Sequence;
    for (const std::string& s : v.strings) n.items.push_back(scalarNode(s, true, loc));
    return n;
  }
  if (usd::isNumeric(v.kind)) {
    const Kind component = usd::componentKind(v.kind);
    if (!v.isArray && usd::componentCount(v.kind) == 1 && !v.numbers.empty())
      return scalarNode(numberText(component, v.numbers[0]), false, loc);
    n.kind = RawNode::Kind::Sequence;
    for (double x : v.numbers) n.items.push_back(scalarNode(numberText(component, x), false, loc));
    return n;
  }
  return n;  // anything else: null, which the section readers report
}

// `prefix0`, `prefix1`, ... of a dictionary in their numeric order (a
// dictionary's keys are sorted as text: event10 before event2).
std::vector<const RawNode*> numbered(const RawNode& map, const std::string& prefix) {
  std::vector<std::pair<long, const RawNode*>> items;
  for (const RawEntry& e : map.entries)
    if (e.key.scalar.rfind(prefix, 0) == 0 && e.key.scalar.size() > prefix.size())
      items.emplace_back(std::strtol(e.key.scalar.c_str() + prefix.size(), nullptr, 10), &e.value);
  std::sort(items.begin(), items.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<const RawNode*> out;
  for (const auto& item : items) out.push_back(item.second);
  return out;
}

// A payload's entries in the order the exporter listed them (`<name>_keys`),
// since a dictionary keeps its keys sorted.
void restoreOrder(RawNode& event, const std::string& name) {
  RawNode* payload = nullptr;
  const RawNode* keys = nullptr;
  for (RawEntry& e : event.entries) {
    if (e.key.scalar == name) payload = &e.value;
    if (e.key.scalar == name + "_keys") keys = &e.value;
  }
  if (payload && payload->isMap() && keys && keys->isSequence()) {
    std::vector<RawEntry> ordered;
    for (const RawNode& key : keys->items)
      for (const RawEntry& e : payload->entries)
        if (e.key.scalar == key.scalar) ordered.push_back(e);
    if (ordered.size() == payload->entries.size()) payload->entries = std::move(ordered);
  }
  event.entries.erase(std::remove_if(event.entries.begin(), event.entries.end(),
                                     [&](const RawEntry& e) { return e.key.scalar == name + "_keys"; }),
                      event.entries.end());
}

}  // namespace

bool importUsdSceneSettings(const usd::ComposedStage& composed, Scene& scene, Diagnostics& diag) {
  auto data = composed.layerMetadata.find("customLayerData");
  if (data == composed.layerMetadata.end() || data->second.kind != Kind::Dictionary || !data->second.dictionary)
    return false;
  auto settings = data->second.dictionary->find("sdgbehave");
  if (settings == data->second.dictionary->end()) return false;
  const SourceLoc loc{composed.rootLayer, 1, 1};
  RawNode top = toNode(settings->second, loc);
  if (!top.isMap()) {
    diag.error(loc, "customLayerData[\"sdgbehave\"]: expected a dictionary of sdgbehave's settings");
    return true;
  }
  // The writers and events were written as numbered dictionaries; the
  // section readers take lists.
  for (RawEntry& e : top.entries) {
    if (!e.value.isMap() || (e.key.scalar != "writers" && e.key.scalar != "events")) continue;
    const bool writers = e.key.scalar == "writers";
    RawNode list;
    list.kind = RawNode::Kind::Sequence;
    list.loc = loc;
    for (const RawNode* item : numbered(e.value, writers ? "writer" : "event")) {
      list.items.push_back(*item);
      if (!writers) {
        restoreOrder(list.items.back(), "payload");
        restoreOrder(list.items.back(), "wait_for");
      }
    }
    e.key.scalar = writers ? "writer" : "events";
    e.value = std::move(list);
  }
  MapReader reader(top, "customLayerData[\"sdgbehave\"]", diag);
  if (!reader.ok()) return true;
  readSettingSections(reader, scene, diag);
  reader.allow("behaviorsWithoutScript");  // export's note for people; the prims say it
  reader.finish();
  return true;
}

}  // namespace sdg
