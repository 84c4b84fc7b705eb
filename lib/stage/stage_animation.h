#pragma once
// A stage's own animation: values of prim attributes and transform ops
// given at time codes (a USD stage's time samples, converted to stage
// values by the import: scene_io/usd_animation.h). The table is read-only
// once imported and shared by every copy of the stage; the timeline plays
// it (behavior/animation_playback.h): at each update, before behaviors, each
// animated value is written at the time code the timeline has reached.
//
// Values are computed from the time code alone, never accumulated, so a
// shard that starts at frame k shows what a whole run shows at frame k.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "stage/value.h"

namespace sdg {

class Stage;

// How timeline seconds become the source's time codes: time code =
// startTimeCode + seconds * timeCodesPerSecond (a USD layer's metadata).
struct AnimationClock {
  double startTimeCode = 0.0;
  double timeCodesPerSecond = 24.0;
  bool operator==(const AnimationClock&) const = default;
};

// One animated attribute (or transform op) of one prim.
struct AnimatedValue {
  std::string primPath;
  // The attribute's name, or the op's attribute name ("xformOp:translate").
  std::string name;
  bool xformOp = false;
  AnimationClock clock;
  std::vector<double> times;  // time codes, ascending, at least two
  std::vector<Value> values;  // one per time, all of one type
  // What the import wrote there (the start time code's value; nullopt:
  // nothing). A scene that changed it since overrides the samples.
  std::optional<Value> imported;
  // Past the last time, continue the line through the last two samples
  // (linear types only) instead of holding: a USD PointInstancer's
  // positions moving at their authored velocities.
  bool extrapolate = false;

  // The value at `timeCode`: held before the first and after the last
  // time (unless `extrapolate`); between two, linear for numbers, vectors, matrices and numeric
  // arrays of equal length, spherical for quaternions, held for the rest
  // (bool, int, tokens, strings, int arrays), as USD interpolates.
  Value at(double timeCode) const;
};

// The time code of `clock` after `steps` updates of a timeline running at
// `rate` updates a second. Computed as start + steps * tcps / rate so that
// equal rates land exactly on whole time codes (no 1/rate rounding).
double timeCodeAt(const AnimationClock& clock, uint64_t steps, double rate);

class StageAnimation {
 public:
  void add(AnimatedValue value);
  bool empty() const { return values_.empty(); }
  size_t size() const { return values_.size(); }
  const std::vector<std::shared_ptr<const AnimatedValue>>& values() const { return values_; }
  // The animated value of a prim's attribute or op; null when it is not animated.
  const AnimatedValue* find(std::string_view primPath, std::string_view name) const;
  // Forgets the animated values whose target the scene has changed since
  // the import (a YAML entry or --set override of a mounted USD prim's
  // animated translate): a stronger opinion than the samples, as in USD.
  void dropOverridden(const Stage& stage);

 private:
  std::vector<std::shared_ptr<const AnimatedValue>> values_;
};

// Writes `value` into its prim (the op's value, or the attribute's);
// false when the prim, or the op, is no longer there (removed or replaced
// by a behavior: nothing is written).
bool writeAnimatedValue(Stage& stage, const AnimatedValue& animated, const Value& value);
// The value the stage holds now where `animated` writes; nullopt when the
// prim or op is gone or the attribute is not authored.
std::optional<Value> readAnimatedTarget(const Stage& stage, const AnimatedValue& animated);

}  // namespace sdg
