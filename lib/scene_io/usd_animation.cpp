#include "scene_io/usd_animation.h"

#include <algorithm>
#include <map>
#include <set>

namespace sdg {
namespace {

const std::string kOpPrefix = "op ";  // keys of ops among attribute names (no attribute has a space)

// What the sampler wrote: attributes by name, ops by "op " + attribute name.
std::map<std::string, Value> valuesOf(const Prim& prim) {
  std::map<std::string, Value> out;
  for (const auto& [name, attr] : prim.attributes()) out.emplace(name, attr.value);
  for (const XformOp& op : prim.xformOps()) out.emplace(kOpPrefix + op.attributeName(), op.value);
  return out;
}

std::optional<double> numberField(const usd::ComposedStage& composed, const char* name) {
  auto it = composed.layerMetadata.find(name);
  if (it == composed.layerMetadata.end() || !usd::isNumeric(it->second.kind) || it->second.isArray ||
      it->second.numbers.empty())
    return std::nullopt;
  return it->second.numbers[0];
}

}  // namespace

bool usdPrimIsAnimated(const usd::ComposedPrim& prim) {
  for (const usd::ComposedProperty& p : prim.properties)
    if (p.samples && p.samples->varies()) return true;
  return false;
}

std::optional<double> usdAuthoredRate(const usd::ComposedStage& composed) {
  for (const char* name : {"timeCodesPerSecond", "framesPerSecond"})
    if (std::optional<double> rate = numberField(composed, name); rate && *rate > 0) return rate;
  return std::nullopt;
}

AnimationClock usdAnimationClock(const usd::ComposedStage& composed) {
  AnimationClock clock;
  clock.startTimeCode = composed.timeCode;
  clock.timeCodesPerSecond = usdAuthoredRate(composed).value_or(24.0);
  return clock;
}

usd::ComposedPrim usdPrimAt(const usd::ComposedPrim& prim, double timeCode) {
  usd::ComposedPrim at = prim;
  for (usd::ComposedProperty& p : at.properties)
    if (p.samples && p.samples->varies()) p.value = p.samples->valueAt(timeCode);
  return at;
}

void recordUsdPrimAnimation(const usd::ComposedPrim& prim, const Prim& imported, const AnimationClock& clock,
                            const UsdPrimSampler& sample, StageAnimation& animation) {
  std::set<double> timeSet;
  for (const usd::ComposedProperty& p : prim.properties)
    if (p.samples && p.samples->varies())
      for (double t : p.samples->stageTimes()) timeSet.insert(t);
  const std::vector<double> times(timeSet.begin(), timeSet.end());
  if (times.size() < 2) return;
  auto sampled = [&](double t) {
    Prim scratch(imported.path(), imported.type(), nullptr);
    sample(usdPrimAt(prim, t), scratch);
    return valuesOf(scratch);
  };
  // Two passes, so that only the values that change are ever held for
  // every time (a static mesh under an animated transform is not copied
  // once per sample).
  const std::map<std::string, Value> first = sampled(times.front());
  std::set<std::string> varying;
  for (size_t i = 1; i < times.size(); ++i)
    for (const auto& [name, value] : sampled(times[i])) {
      auto f = first.find(name);
      if (f == first.end() || !(f->second == value) || f->second.type() != value.type()) varying.insert(name);
    }
  if (varying.empty()) return;
  std::map<std::string, AnimatedValue> tracks;
  std::set<std::string> incomplete;  // missing at some time (a blocked sample): not animated
  for (double t : times) {
    const std::map<std::string, Value> values = sampled(t);
    for (const std::string& name : varying) {
      auto v = values.find(name);
      AnimatedValue& track = tracks[name];
      if (v == values.end() || (!track.values.empty() && track.values.front().type() != v->second.type())) {
        incomplete.insert(name);
        continue;
      }
      track.times.push_back(t);
      track.values.push_back(v->second);
    }
  }
  const std::map<std::string, Value> atImport = valuesOf(imported);
  for (auto& [name, track] : tracks) {
    if (incomplete.count(name)) continue;
    track.primPath = imported.path();
    if (auto it = atImport.find(name); it != atImport.end()) track.imported = it->second;
    track.xformOp = name.rfind(kOpPrefix, 0) == 0;
    track.name = track.xformOp ? name.substr(kOpPrefix.size()) : name;
    track.clock = clock;
    animation.add(std::move(track));
  }
}

}  // namespace sdg
