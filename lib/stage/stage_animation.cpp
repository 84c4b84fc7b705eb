#include "stage/stage_animation.h"

#include <algorithm>

#include "stage/stage.h"

namespace sdg {
namespace {

template <typename T>
T mix(const T& a, const T& b, double t) {
  return a + (b - a) * static_cast<typename T::Scalar>(t);
}

// Between two values of one type, at t in (0, 1); nullopt where USD holds
// the earlier value (discrete types, arrays of different lengths).
std::optional<Value> interpolate(const Value& a, const Value& b, double t) {
  if (a.type() != b.type()) return std::nullopt;
  switch (a.type()) {
    case ValueType::Float: {
      const float x = a.get<float>(), y = b.get<float>();
      return Value::makeFloat(x + (y - x) * static_cast<float>(t));
    }
    case ValueType::Double: {
      const double x = a.get<double>(), y = b.get<double>();
      return Value::makeDouble(x + (y - x) * t);
    }
    case ValueType::Float2: {
      const Vec2f v = mix(a.get<Vec2f>(), b.get<Vec2f>(), t);
      return Value::makeFloat2(v.x(), v.y());
    }
    case ValueType::Float3: return Value::makeFloat3(mix(a.get<Vec3f>(), b.get<Vec3f>(), t));
    case ValueType::Color3f: return Value::makeColor3f(mix(a.get<Vec3f>(), b.get<Vec3f>(), t));
    case ValueType::Double3: return Value::makeDouble3(mix(a.get<Vec3d>(), b.get<Vec3d>(), t));
    case ValueType::Vector3d: return Value::makeVector3d(mix(a.get<Vec3d>(), b.get<Vec3d>(), t));
    // Eigen's slerp takes the shorter arc, as USD's does.
    case ValueType::Quatf: return Value::makeQuatf(a.get<Quatf>().slerp(static_cast<float>(t), b.get<Quatf>()));
    case ValueType::Quatd: return Value::makeQuatd(a.get<Quatd>().slerp(t, b.get<Quatd>()));
    case ValueType::Matrix4d: return Value::makeMatrix4d(mix(a.get<Matrix4d>(), b.get<Matrix4d>(), t));
    case ValueType::FloatArray:
    case ValueType::Point3fArray:
    case ValueType::Normal3fArray:
    case ValueType::TexCoord2fArray: {
      const FloatArray& x = a.get<FloatArray>();
      const FloatArray& y = b.get<FloatArray>();
      if (x.size() != y.size()) return std::nullopt;
      std::vector<float> flat(x.size());
      const float w = static_cast<float>(t);
      for (size_t i = 0; i < flat.size(); ++i) flat[i] = x[i] + (y[i] - x[i]) * w;
      return Value::makeFloatArray(a.type(), std::move(flat));
    }
    default: return std::nullopt;
  }
}

}  // namespace

Value AnimatedValue::at(double timeCode) const {
  auto upper = std::upper_bound(times.begin(), times.end(), timeCode);
  if (upper == times.begin()) return values.front();
  if (upper == times.end() && extrapolate && times.size() >= 2 && timeCode > times.back()) {
    const size_t n = times.size();
    const double t = (timeCode - times[n - 2]) / (times[n - 1] - times[n - 2]);
    if (std::optional<Value> line = interpolate(values[n - 2], values[n - 1], t)) return std::move(*line);
    return values.back();
  }
  const size_t lo = static_cast<size_t>(upper - times.begin()) - 1;
  if (upper == times.end() || times[lo] == timeCode) return values[lo];
  const double t = (timeCode - times[lo]) / (times[lo + 1] - times[lo]);
  const Value& a = values[lo];
  const Value& b = values[lo + 1];
  if (std::optional<Value> mixed = interpolate(a, b, t)) return std::move(*mixed);
  return a;
}

double timeCodeAt(const AnimationClock& clock, uint64_t steps, double rate) {
  return clock.startTimeCode + static_cast<double>(steps) * clock.timeCodesPerSecond / rate;
}

void StageAnimation::add(AnimatedValue value) {
  values_.push_back(std::make_shared<const AnimatedValue>(std::move(value)));
}

const AnimatedValue* StageAnimation::find(std::string_view primPath, std::string_view name) const {
  for (const auto& v : values_)
    if (v->primPath == primPath && v->name == name) return v.get();
  return nullptr;
}

void StageAnimation::dropOverridden(const Stage& stage) {
  std::erase_if(values_, [&](const std::shared_ptr<const AnimatedValue>& v) {
    return readAnimatedTarget(stage, *v) != v->imported;
  });
}

bool writeAnimatedValue(Stage& stage, const AnimatedValue& animated, const Value& value) {
  Prim* prim = stage.find(animated.primPath);
  if (!prim) return false;
  if (animated.xformOp) {
    XformOp* op = prim->findXformOp(animated.name);
    if (!op || op->value.type() != value.type()) return false;
    op->value = value;
    return true;
  }
  if (Attribute* attr = prim->findAttribute(animated.name)) attr->value = value;
  else prim->setAttribute(animated.name, value);
  return true;
}

std::optional<Value> readAnimatedTarget(const Stage& stage, const AnimatedValue& animated) {
  const Prim* prim = stage.find(animated.primPath);
  if (!prim) return std::nullopt;
  if (animated.xformOp) {
    for (const XformOp& op : prim->xformOps())
      if (op.attributeName() == animated.name) return op.value;
    return std::nullopt;
  }
  if (const Attribute* attr = prim->findAttribute(animated.name)) return attr->value;
  return std::nullopt;
}

}  // namespace sdg
