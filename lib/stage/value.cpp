#include "stage/value.h"

#include <array>

#include "core/text.h"

namespace sdg {
namespace {
struct TypeInfo {
  ValueType type;
  std::string_view name;
  std::string_view shape;
};
constexpr std::array kTypes = {
    TypeInfo{ValueType::Bool, "bool", "true or false"},
    TypeInfo{ValueType::Int, "int", "an integer"},
    TypeInfo{ValueType::UInt, "uint", "a non-negative integer"},
    TypeInfo{ValueType::Float, "float", "a number"},
    TypeInfo{ValueType::Double, "double", "a number"},
    TypeInfo{ValueType::Int2, "int2", "a list of 2 integers"},
    TypeInfo{ValueType::Float2, "float2", "a list of 2 numbers"},
    TypeInfo{ValueType::Float3, "float3", "a list of 3 numbers"},
    TypeInfo{ValueType::Color3f, "color3f", "a list of 3 numbers (r, g, b)"},
    TypeInfo{ValueType::Double3, "double3", "a list of 3 numbers"},
    TypeInfo{ValueType::Vector3d, "vector3d", "a list of 3 numbers"},
    TypeInfo{ValueType::Quatf, "quatf", "a list of 4 numbers (w, x, y, z)"},
    TypeInfo{ValueType::Quatd, "quatd", "a list of 4 numbers (w, x, y, z)"},
    TypeInfo{ValueType::Matrix4d, "matrix4d", "4 rows of 4 numbers (USD row-vector layout)"},
    TypeInfo{ValueType::String, "string", "a string"},
    TypeInfo{ValueType::Token, "token", "a token (a string from a fixed set)"},
    TypeInfo{ValueType::Asset, "asset", "an asset path (a string)"},
    TypeInfo{ValueType::AssetArray, "asset[]", "a list of asset paths"},
    TypeInfo{ValueType::StringArray, "string[]", "a list of strings"},
    TypeInfo{ValueType::IntArray, "int[]", "a list of integers"},
    TypeInfo{ValueType::FloatArray, "float[]", "a list of numbers"},
    TypeInfo{ValueType::Point3fArray, "point3f[]", "a list of points (lists of 3 numbers)"},
    TypeInfo{ValueType::Normal3fArray, "normal3f[]", "a list of normals (lists of 3 numbers)"},
    TypeInfo{ValueType::TexCoord2fArray, "texCoord2f[]", "a list of texture coordinates (lists of 2 numbers)"},
    TypeInfo{ValueType::Color3fArray, "color3f[]", "a list of colours (lists of 3 numbers r, g, b)"},
};
constexpr std::array<ValueType, kTypes.size()> kTypeList = [] {
  std::array<ValueType, kTypes.size()> list{};
  for (size_t i = 0; i < kTypes.size(); ++i) list[i] = kTypes[i].type;
  return list;
}();

const TypeInfo& info(ValueType type) {
  for (const TypeInfo& t : kTypes)
    if (t.type == type) return t;
  return kTypes[0];
}

std::string listText(std::initializer_list<std::string> items) {
  std::string out = "[";
  bool first = true;
  for (const std::string& item : items) {
    if (!first) out += ", ";
    out += item;
    first = false;
  }
  return out + "]";
}
}  // namespace

int arrayWidth(ValueType type) {
  switch (type) {
    case ValueType::IntArray:
    case ValueType::FloatArray: return 1;
    case ValueType::TexCoord2fArray: return 2;
    case ValueType::Point3fArray:
    case ValueType::Normal3fArray:
    case ValueType::Color3fArray: return 3;
    default: return 0;
  }
}

std::span<const ValueType> allValueTypes() { return kTypeList; }
std::string_view valueTypeName(ValueType type) { return info(type).name; }
std::string_view valueTypeShape(ValueType type) { return info(type).shape; }

std::optional<ValueType> valueTypeFromName(std::string_view name) {
  for (const TypeInfo& t : kTypes)
    if (t.name == name) return t.type;
  return std::nullopt;
}

bool Value::operator==(const Value& other) const {
  if (type_ != other.type_) return false;
  // Quaternions compare by coefficients (Eigen has no operator== for them).
  if (type_ == ValueType::Quatf) return get<Quatf>().coeffs() == other.get<Quatf>().coeffs();
  if (type_ == ValueType::Quatd) return get<Quatd>().coeffs() == other.get<Quatd>().coeffs();
  return storage_ == other.storage_;
}

std::string Value::toString() const {
  using text::formatDouble;
  using text::formatFloat;
  switch (type_) {
    case ValueType::Bool: return get<bool>() ? "true" : "false";
    case ValueType::Int: return std::to_string(get<int32_t>());
    case ValueType::UInt: return std::to_string(get<uint32_t>());
    case ValueType::Float: return formatFloat(get<float>());
    case ValueType::Double: return formatDouble(get<double>());
    case ValueType::Int2: {
      const Vec2i& v = get<Vec2i>();
      return listText({std::to_string(v.x()), std::to_string(v.y())});
    }
    case ValueType::Float2: {
      const Vec2f& v = get<Vec2f>();
      return listText({formatFloat(v.x()), formatFloat(v.y())});
    }
    case ValueType::Float3:
    case ValueType::Color3f: {
      const Vec3f& v = get<Vec3f>();
      return listText({formatFloat(v.x()), formatFloat(v.y()), formatFloat(v.z())});
    }
    case ValueType::Double3:
    case ValueType::Vector3d: {
      const Vec3d& v = get<Vec3d>();
      return listText({formatDouble(v.x()), formatDouble(v.y()), formatDouble(v.z())});
    }
    case ValueType::Quatf: {
      const Quatf& q = get<Quatf>();
      return listText({formatFloat(q.w()), formatFloat(q.x()), formatFloat(q.y()), formatFloat(q.z())});
    }
    case ValueType::Quatd: {
      const Quatd& q = get<Quatd>();
      return listText({formatDouble(q.w()), formatDouble(q.x()), formatDouble(q.y()), formatDouble(q.z())});
    }
    case ValueType::Matrix4d: {
      // Written as USD writes it: rows of the row-vector matrix = our columns.
      const Matrix4d& m = get<Matrix4d>();
      std::string out = "[";
      for (int c = 0; c < 4; ++c) {
        if (c) out += ", ";
        out += listText({formatDouble(m(0, c)), formatDouble(m(1, c)), formatDouble(m(2, c)),
                         formatDouble(m(3, c))});
      }
      return out + "]";
    }
    case ValueType::String:
    case ValueType::Token:
    case ValueType::Asset: return text::quote(get<std::string>());
    case ValueType::AssetArray:
    case ValueType::StringArray: {
      std::string out = "[";
      const auto& items = get<std::vector<std::string>>();
      for (size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + text::quote(items[i]);
      return out + "]";
    }
    case ValueType::IntArray:
    case ValueType::FloatArray:
    case ValueType::Point3fArray:
    case ValueType::Normal3fArray:
    case ValueType::Color3fArray:
    case ValueType::TexCoord2fArray: {
      // Messages show the first items only: a mesh has millions.
      const size_t width = size_t(arrayWidth(type_));
      const size_t count = type_ == ValueType::IntArray ? get<IntArray>().size() : get<FloatArray>().size() / width;
      std::string out = "[";
      for (size_t i = 0; i < count && i < 4; ++i) {
        std::vector<std::string> parts;
        for (size_t k = 0; k < width; ++k)
          parts.push_back(type_ == ValueType::IntArray ? std::to_string(get<IntArray>()[i])
                                                       : formatFloat(get<FloatArray>()[i * width + k]));
        out += (i ? ", " : "") + (width == 1 ? parts[0] : "[" + text::join(parts, ", ") + "]");
      }
      if (count > 4) out += ", ... (" + std::to_string(count) + " items)";
      return out + "]";
    }
  }
  return {};
}

AttributeSpec makeAttributeSpec(std::string name, Value fallback, std::string doc) {
  AttributeSpec spec;
  spec.name = std::move(name);
  spec.type = fallback.type();
  spec.defaultValue = std::move(fallback);
  spec.doc = std::move(doc);
  return spec;
}

}  // namespace sdg
