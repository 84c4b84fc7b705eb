// Composition: list ops composed over a layer stack, and attribute values
// resolved over a prim index at a time code (time samples with layer
// offsets applied, linear interpolation where USD interpolates).
#include <algorithm>
#include <cmath>

#include "usd/compose_internal.h"
#include "usd/sdf_path.h"

namespace sdg::usd::detail {

namespace {

template <class T>
ListOp<SourcedItem<T>> sourced(const ListOp<T>& op, size_t layerIndex) {
  auto wrap = [&](const std::vector<T>& items) {
    std::vector<SourcedItem<T>> out;
    out.reserve(items.size());
    for (const T& item : items) out.push_back({item, layerIndex});
    return out;
  };
  ListOp<SourcedItem<T>> out;
  out.isExplicit = op.isExplicit;
  out.explicitItems = wrap(op.explicitItems);
  out.addedItems = wrap(op.addedItems);
  out.prependedItems = wrap(op.prependedItems);
  out.appendedItems = wrap(op.appendedItems);
  out.deletedItems = wrap(op.deletedItems);
  out.orderedItems = wrap(op.orderedItems);
  return out;
}

// A list field composed over a layer stack, weakest layer first; `asListOp`
// gives a layer's value as a list op (null when the field holds none).
template <class T, class AsListOp>
std::vector<SourcedItem<T>> composeOverStack(const LayerStack& stack, const std::string& path, const char* fieldName,
                                             AsListOp asListOp) {
  std::vector<SourcedItem<T>> result;
  for (size_t i = stack.layers.size(); i-- > 0;) {
    const Spec* spec = stack.layers[i]->spec(path);
    const Value* v = spec ? spec->field(fieldName) : nullptr;
    if (!v) continue;
    if (std::optional<ListOp<T>> op = asListOp(*v)) result = sourced(*op, i).applyTo(result);
  }
  return result;
}

template <class T>
ListOp<T> explicitList(std::vector<T> items) {
  ListOp<T> op;
  op.isExplicit = true;
  op.explicitItems = std::move(items);
  return op;
}

}  // namespace

std::vector<SourcedItem<std::string>> composeTextListOp(const LayerStack& stack, const std::string& path,
                                                        const char* fieldName) {
  return composeOverStack<std::string>(stack, path, fieldName, [](const Value& v) -> std::optional<ListOp<std::string>> {
    if (v.textListOp) return *v.textListOp;
    if (v.kind == Kind::PathVector || v.kind == Kind::TokenVector || v.kind == Kind::StringVector)
      return explicitList(v.strings);  // a plain vector: an explicit list
    return std::nullopt;
  });
}

std::vector<SourcedItem<Reference>> composeReferenceListOp(const LayerStack& stack, const std::string& path,
                                                           const char* fieldName) {
  return composeOverStack<Reference>(stack, path, fieldName, [](const Value& v) -> std::optional<ListOp<Reference>> {
    if (v.referenceListOp) return *v.referenceListOp;
    if (v.references) return explicitList(*v.references);  // a single reference or payload (crate 0.8's payload field)
    return std::nullopt;
  });
}

namespace {

bool isQuat(Kind kind) { return kind == Kind::Quath || kind == Kind::Quatf || kind == Kind::Quatd; }

bool interpolates(Kind kind) {
  switch (kind) {
    case Kind::Half: case Kind::Float: case Kind::Double: case Kind::TimeCode:
    case Kind::Vec2h: case Kind::Vec2f: case Kind::Vec2d:
    case Kind::Vec3h: case Kind::Vec3f: case Kind::Vec3d:
    case Kind::Vec4h: case Kind::Vec4f: case Kind::Vec4d:
    case Kind::Quath: case Kind::Quatf: case Kind::Quatd:
    case Kind::Matrix2d: case Kind::Matrix3d: case Kind::Matrix4d: return true;
    default: return false;
  }
}

bool singlePrecision(Kind kind) {
  return kind == Kind::Float || kind == Kind::Vec2f || kind == Kind::Vec3f || kind == Kind::Vec4f ||
         kind == Kind::Quatf;
}

// Spherical interpolation of (real, i, j, k) quaternions along the shorter arc.
void slerp(const double* a, const double* b, double t, double* out) {
  double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
  double sign = dot < 0 ? -1.0 : 1.0;
  dot *= sign;
  double wa = 1 - t, wb = t;
  if (dot < 0.9995) {
    double theta = std::acos(std::min(1.0, dot));
    double s = std::sin(theta);
    wa = std::sin((1 - t) * theta) / s;
    wb = std::sin(t * theta) / s;
  }
  double norm = 0;
  for (int i = 0; i < 4; ++i) {
    out[i] = wa * a[i] + wb * sign * b[i];
    norm += out[i] * out[i];
  }
  norm = std::sqrt(norm);
  if (norm > 0)
    for (int i = 0; i < 4; ++i) out[i] /= norm;
}

}  // namespace

std::optional<Value> interpolate(const Value& a, const Value& b, double t) {
  if (a.kind != b.kind || a.isArray != b.isArray || !interpolates(a.kind) || a.numbers.size() != b.numbers.size())
    return std::nullopt;
  Value out = a;
  if (isQuat(a.kind)) {
    for (size_t i = 0; i + 4 <= a.numbers.size(); i += 4) slerp(&a.numbers[i], &b.numbers[i], t, &out.numbers[i]);
  } else {
    for (size_t i = 0; i < a.numbers.size(); ++i) out.numbers[i] = a.numbers[i] + (b.numbers[i] - a.numbers[i]) * t;
  }
  if (singlePrecision(a.kind))
    for (double& x : out.numbers) x = static_cast<double>(static_cast<float>(x));
  return out;
}

// The value of time samples at `time` (layer time): held before the first
// and after the last sample, interpolated between two (held when either is
// a block or the type does not interpolate).
Value sampleAt(const TimeSamples& samples, double time) {
  const auto& times = samples.times;
  auto upper = std::upper_bound(times.begin(), times.end(), time);
  if (upper == times.begin()) return samples.values.front();
  size_t lo = static_cast<size_t>(upper - times.begin()) - 1;
  if (upper == times.end() || times[lo] == time) return samples.values[lo];
  size_t hi = lo + 1;
  const Value& a = samples.values[lo];
  const Value& b = samples.values[hi];
  if (a.kind == Kind::ValueBlock || b.kind == Kind::ValueBlock) return a;
  double t = (time - times[lo]) / (times[hi] - times[lo]);
  if (std::optional<Value> mixed = interpolate(a, b, t)) return std::move(*mixed);
  return a;
}


}  // namespace sdg::usd::detail

namespace sdg::usd {

std::vector<double> AttributeSamples::stageTimes() const {
  std::vector<double> out;
  out.reserve(samples->times.size());
  for (double t : samples->times) out.push_back(toStage.offset + toStage.scale * t);
  if (toStage.scale < 0) std::reverse(out.begin(), out.end());
  return out;
}

Value AttributeSamples::valueAt(double stageTime) const {
  const double layerTime = toStage.scale != 0 ? (stageTime - toStage.offset) / toStage.scale : stageTime;
  Value v = detail::sampleAt(*samples, layerTime);
  if (v.kind == Kind::ValueBlock) return {};
  return v;
}

bool AttributeSamples::varies() const {
  const auto& values = samples->values;
  for (size_t i = 1; i < values.size(); ++i)
    if (!(values[i] == values[0])) return true;
  return false;
}

}  // namespace sdg::usd

namespace sdg::usd::detail {

ResolvedValue resolveAttributeValue(const PrimIndex& index, const std::string& propertyName, double time) {
  for (int n : index.order) {
    const Node& node = index.nodes[static_cast<size_t>(n)];
    if (!node.hasSpecs) continue;
    std::string propPath = path::property(node.path, propertyName);
    for (size_t i = 0; i < node.stack->layers.size(); ++i) {
      const Spec* spec = node.stack->layers[i]->spec(propPath);
      if (!spec) continue;
      const Value* samples = spec->field(field::kTimeSamples);
      if (samples && samples->timeSamples && !samples->timeSamples->times.empty() &&
          samples->timeSamples->times.size() == samples->timeSamples->values.size()) {
        auto kept = std::make_shared<AttributeSamples>();
        kept->samples = samples->timeSamples;
        kept->toStage = concat(node.offsetToRoot, node.stack->offsets[i]);
        // A sample blocked at `time` leaves no value now, but the samples
        // are kept: the value may come back at another time.
        return {kept->valueAt(time), true, node.stack->layers[i], std::move(kept)};
      }
      if (const Value* value = spec->field(field::kDefault)) {
        if (value->kind == Kind::ValueBlock) return {};
        return {*value, false, node.stack->layers[i], nullptr};
      }
    }
  }
  return {};
}

}  // namespace sdg::usd::detail
