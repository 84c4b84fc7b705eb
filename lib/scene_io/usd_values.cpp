// Composed USD values (usd/value.h: numbers kept as doubles, the USD type
// in `kind`) as the stage's typed values.
#include "scene_io/usd_import_internal.h"

namespace sdg::usd_map {
namespace {

// Numbers of one element: the scalar, or the first item of a one-item array
// (USD writes a constant displayColor as color3f[] of one item).
const double* elementNumbers(const usd::Value& v, size_t width) {
  if (!usd::isNumeric(v.kind) || size_t(usd::componentCount(v.kind)) != width) return nullptr;
  if (v.isArray && v.numbers.size() != width) return nullptr;
  return v.numbers.size() == width ? v.numbers.data() : nullptr;
}

}  // namespace

std::optional<Value> toStageValue(const usd::Value& v, ValueType type) {
  if (const int width = arrayWidth(type)) {
    if (!v.isArray || !usd::isNumeric(v.kind) || usd::componentCount(v.kind) != width) return std::nullopt;
    if (type == ValueType::IntArray) {
      std::vector<int32_t> items;
      items.reserve(v.numbers.size());
      for (double d : v.numbers) items.push_back(static_cast<int32_t>(d));
      return Value::makeIntArray(std::move(items));
    }
    std::vector<float> items;
    items.reserve(v.numbers.size());
    for (double d : v.numbers) items.push_back(static_cast<float>(d));
    return Value::makeFloatArray(type, std::move(items));
  }
  switch (type) {
    case ValueType::Bool:
    case ValueType::Int:
    case ValueType::UInt:
    case ValueType::Float:
    case ValueType::Double: {
      const double* n = elementNumbers(v, 1);
      if (!n) return std::nullopt;
      if (type == ValueType::Bool) return Value::makeBool(*n != 0);
      if (type == ValueType::Int) return Value::makeInt(static_cast<int32_t>(*n));
      if (type == ValueType::UInt) return *n < 0 ? std::nullopt : std::optional(Value::makeUInt(static_cast<uint32_t>(*n)));
      if (type == ValueType::Float) return Value::makeFloat(static_cast<float>(*n));
      return Value::makeDouble(*n);
    }
    case ValueType::Int2: {
      const double* n = elementNumbers(v, 2);
      if (!n) return std::nullopt;
      return Value::makeInt2(static_cast<int32_t>(n[0]), static_cast<int32_t>(n[1]));
    }
    case ValueType::Float2: {
      const double* n = elementNumbers(v, 2);
      if (!n) return std::nullopt;
      return Value::makeFloat2(static_cast<float>(n[0]), static_cast<float>(n[1]));
    }
    case ValueType::Float3:
    case ValueType::Color3f:
    case ValueType::Double3:
    case ValueType::Vector3d: {
      const double* n = elementNumbers(v, 3);
      if (!n) return std::nullopt;
      const Vec3d d(n[0], n[1], n[2]);
      if (type == ValueType::Float3) return Value::makeFloat3(d.cast<float>());
      if (type == ValueType::Color3f) return Value::makeColor3f(d.cast<float>());
      if (type == ValueType::Double3) return Value::makeDouble3(d);
      return Value::makeVector3d(d);
    }
    case ValueType::Quatf:
    case ValueType::Quatd: {
      // Stored (real, i, j, k) whatever the layer's form.
      if (v.isArray || (v.kind != usd::Kind::Quath && v.kind != usd::Kind::Quatf && v.kind != usd::Kind::Quatd))
        return std::nullopt;
      const auto& n = v.numbers;
      if (type == ValueType::Quatf)
        return Value::makeQuatf(Quatf(float(n[0]), float(n[1]), float(n[2]), float(n[3])));
      return Value::makeQuatd(Quatd(n[0], n[1], n[2], n[3]));
    }
    case ValueType::Matrix4d: {
      if (v.isArray || v.kind != usd::Kind::Matrix4d) return std::nullopt;
      // USD's rows (row-vector convention) are our columns.
      Matrix4d m;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m(c, r) = v.numbers[size_t(r * 4 + c)];
      return Value::makeMatrix4d(m);
    }
    case ValueType::String:
    case ValueType::Token:
    case ValueType::Asset: {
      if (v.isArray || !usd::isText(v.kind) || v.strings.size() != 1) return std::nullopt;
      if (type == ValueType::String) return Value::makeString(v.strings[0]);
      if (type == ValueType::Token) return Value::makeToken(v.strings[0]);
      return Value::makeAsset(v.strings[0]);
    }
    case ValueType::AssetArray:
    case ValueType::StringArray:
      if (!usd::isText(v.kind)) return std::nullopt;
      return type == ValueType::AssetArray ? Value::makeAssetArray(v.strings) : Value::makeStringArray(v.strings);
    default: return std::nullopt;
  }
}

}  // namespace sdg::usd_map
