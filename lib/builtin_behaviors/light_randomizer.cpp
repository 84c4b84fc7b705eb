// lightRandomizer — random colour and intensity for lights.
//
// Exposed variables (exposedVar:lightRandomizer:*):
//   range:minColor   color3f  (0.1, 0.1, 0.1)  per-channel lower bound
//   range:maxColor   color3f  (0.9, 0.9, 0.9)  per-channel upper bound
//   range:intensity  float2   (1000, 20000)    (min, max) of inputs:intensity
//   includeChildren  bool     true             every light prim below too
//   interval         uint     0
//   seed             int      -1
//
// Acts on light prims only (DistantLight, SphereLight, RectLight, DiskLight,
// CylinderLight, DomeLight). Per light and apply: r, g, b drawn in that
// order into inputs:color, then the intensity into inputs:intensity. On stop
// authored values come back, and attributes the light did not author are
// removed again (Isaac Sim leaves them with their last random value; here the
// stage after stop equals the stage before play).
//
// Example:
//   behaviors:
//     lightRandomizer: {interval: 4, range:intensity: [20000, 120000]}
//
// Events: none (timeline driven).
#include <optional>

#include "behavior/interval_behavior.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "builtin_behaviors/spec_helpers.h"
#include "core/log.h"

namespace sdg {
namespace {

class LightRandomizer final : public IntervalBehavior {
  struct Entry {
    std::string path;
    std::optional<Value> color;      // authored before play, or nothing
    std::optional<Value> intensity;
  };

  void setup() override {
    minColor_ = var<Vec3f>("range:minColor");
    maxColor_ = var<Vec3f>("range:maxColor");
    intensity_ = var<Vec2f>("range:intensity");
    if (isSetUp()) return;
    rng_ = makeRng(var<int32_t>("seed"));
    entries_.clear();
    for (Prim* p : selectPrims(var<bool>("includeChildren"), [](const Prim& q) { return q.typeInfo().light; })) {
      Entry e{p->path(), std::nullopt, std::nullopt};
      if (const Attribute* a = p->findAttribute("inputs:color")) e.color = a->value;
      if (const Attribute* a = p->findAttribute("inputs:intensity")) e.intensity = a->value;
      entries_.push_back(std::move(e));
    }
    if (entries_.empty()) log::warn(primPath() + ": lightRandomizer: no light prims found");
  }

  void apply() override {
    for (const Entry& e : entries_) {
      Prim& p = *stage().find(e.path);
      Vec3f color;
      for (int c = 0; c < 3; ++c) color[c] = static_cast<float>(rng_.uniform(minColor_[c], maxColor_[c]));
      p.setAttribute("inputs:color", Value::makeColor3f(color));
      p.setAttribute("inputs:intensity", Value::makeFloat(static_cast<float>(rng_.uniform(intensity_.x(), intensity_.y()))));
    }
  }

  void restore() override {
    for (const Entry& e : entries_) {
      Prim* p = stage().find(e.path);
      if (!p) continue;
      if (e.color) p->setAttribute("inputs:color", *e.color);
      else p->removeAttribute("inputs:color");
      if (e.intensity) p->setAttribute("inputs:intensity", *e.intensity);
      else p->removeAttribute("inputs:intensity");
    }
    entries_.clear();
  }

  Rng rng_;
  std::vector<Entry> entries_;
  Vec3f minColor_, maxColor_;
  Vec2f intensity_;
};

}  // namespace

BehaviorSpec lightRandomizerSpec() {
  using namespace behaviors;
  BehaviorSpec spec;
  spec.name = "lightRandomizer";
  spec.summary = "Random colour and intensity for light prims.";
  spec.variables = {
      includeChildrenVariable(),
      intervalVariable(),
      variable("range:minColor", Value::makeColor3f({0.1f, 0.1f, 0.1f}), "Per-channel lower bound of the colour."),
      variable("range:maxColor", Value::makeColor3f({0.9f, 0.9f, 0.9f}), "Per-channel upper bound of the colour."),
      variable("range:intensity", Value::makeFloat2(1000.0f, 20000.0f), "(min, max) of inputs:intensity."),
      seedVariable(),
  };
  spec.example = "lightRandomizer: {interval: 4, range:intensity: [20000, 120000]}";
  spec.validate = [](const Prim& prim, Diagnostics& diag) {
    behaviors::checkRange(prim, "lightRandomizer", "range:minColor", "range:maxColor", diag);
    behaviors::checkRange(prim, "lightRandomizer", "range:intensity", "", diag);
  };
  return spec;
}

std::unique_ptr<Behavior> makeLightRandomizer() { return std::make_unique<LightRandomizer>(); }

}  // namespace sdg
