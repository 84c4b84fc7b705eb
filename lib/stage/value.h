#pragma once
// A typed attribute value. The ValueType names the USD type (color3f and
// float3 share a representation, as do string, token and asset); Storage
// holds the bits. Comparisons are exact: a restored stage must equal the
// original bit for bit.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "stage/math_types.h"
#include "stage/shared_array.h"

namespace sdg {

enum class ValueType {
  Bool, Int, UInt, Float, Double,
  Int2, Float2, Float3, Color3f, Double3, Vector3d,
  Quatf, Quatd, Matrix4d,
  String, Token, Asset, AssetArray, StringArray,
  // Numeric arrays (inline mesh geometry), shared between copies:
  // int[] and float[] one number per item; point3f[] and normal3f[] three;
  // texCoord2f[] two; color3f[] three (stored flat).
  IntArray, FloatArray, Point3fArray, Normal3fArray, TexCoord2fArray,
  Color3fArray,  // per-corner displayColor (three numbers per item)
};

// Numbers per item of a numeric array type (0 for every other type).
int arrayWidth(ValueType type);

// Every type, in declaration order (for tables, tests and the schema).
std::span<const ValueType> allValueTypes();
// USD spelling: "float3", "color3f", "asset[]", ...
std::string_view valueTypeName(ValueType type);
std::optional<ValueType> valueTypeFromName(std::string_view name);
// A phrase for messages: "a list of 3 numbers", "true or false", ...
std::string_view valueTypeShape(ValueType type);

using ValueStorage = std::variant<bool, int32_t, uint32_t, float, double, Vec2i, Vec2f, Vec3f, Vec3d,
                                  Quatf, Quatd, Matrix4d, std::string, std::vector<std::string>, IntArray,
                                  FloatArray>;

class Value {
 public:
  Value() = default;  // a Bool false; real values come from the factories
  static Value makeBool(bool v) { return Value(ValueType::Bool, v); }
  static Value makeInt(int32_t v) { return Value(ValueType::Int, v); }
  static Value makeUInt(uint32_t v) { return Value(ValueType::UInt, v); }
  static Value makeFloat(float v) { return Value(ValueType::Float, v); }
  static Value makeDouble(double v) { return Value(ValueType::Double, v); }
  static Value makeInt2(int32_t x, int32_t y) { return Value(ValueType::Int2, Vec2i(x, y)); }
  static Value makeFloat2(float x, float y) { return Value(ValueType::Float2, Vec2f(x, y)); }
  static Value makeFloat3(const Vec3f& v) { return Value(ValueType::Float3, v); }
  static Value makeColor3f(const Vec3f& v) { return Value(ValueType::Color3f, v); }
  static Value makeDouble3(const Vec3d& v) { return Value(ValueType::Double3, v); }
  static Value makeVector3d(const Vec3d& v) { return Value(ValueType::Vector3d, v); }
  static Value makeQuatf(const Quatf& q) { return Value(ValueType::Quatf, q); }
  static Value makeQuatd(const Quatd& q) { return Value(ValueType::Quatd, q); }
  static Value makeMatrix4d(const Matrix4d& m) { return Value(ValueType::Matrix4d, m); }
  static Value makeString(std::string s) { return Value(ValueType::String, std::move(s)); }
  static Value makeToken(std::string s) { return Value(ValueType::Token, std::move(s)); }
  static Value makeAsset(std::string s) { return Value(ValueType::Asset, std::move(s)); }
  static Value makeAssetArray(std::vector<std::string> v) { return Value(ValueType::AssetArray, std::move(v)); }
  static Value makeStringArray(std::vector<std::string> v) { return Value(ValueType::StringArray, std::move(v)); }
  static Value makeIntArray(std::vector<int32_t> v) { return Value(ValueType::IntArray, IntArray(std::move(v))); }
  // FloatArray, Point3fArray, Normal3fArray, TexCoord2fArray: `flat` holds
  // arrayWidth(type) numbers per item.
  static Value makeFloatArray(ValueType type, std::vector<float> flat) {
    return Value(type, FloatArray(std::move(flat)));
  }

  ValueType type() const { return type_; }
  const ValueStorage& storage() const { return storage_; }

  // Typed access; the caller knows the type from the spec it checked against.
  template <typename T>
  const T& get() const { return std::get<T>(storage_); }
  template <typename T>
  T& get() { return std::get<T>(storage_); }

  bool operator==(const Value& other) const;
  // Compact human text: "[1.0, 2.0, 3.0]", "true", "'abc'".
  std::string toString() const;

 private:
  Value(ValueType type, ValueStorage storage) : type_(type), storage_(std::move(storage)) {}
  ValueType type_ = ValueType::Bool;
  ValueStorage storage_ = false;
};

// Specification of one attribute (a prim type's schema attribute, an exposed
// variable of a behavior, or a settings option). One table of these drives
// loading, defaults, `describe`, the YAML writer and the JSON Schema.
// What kind of file an attribute names: Asset and AssetArray values name
// files; a String with a kind other than None is a comma-separated list of
// them. Lets `validate` check every file before a run needs it.
enum class FileKind : uint8_t { None, Mesh, Image, Any };

struct AttributeSpec {
  std::string name;
  ValueType type = ValueType::Bool;
  Value defaultValue;
  std::string doc;
  bool locked = false;                    // read-only for users (informational)
  std::vector<std::string> allowedTokens;  // for Token: the closed set of values
  std::optional<double> minimum;          // inclusive bound for scalars/vectors
  bool primPath = false;                  // a String naming a prim: "" or an existing path
  FileKind files = FileKind::None;        // for Asset/AssetArray: None means Any
};

// A spec whose type is the fallback's type.
AttributeSpec makeAttributeSpec(std::string name, Value fallback, std::string doc);

}  // namespace sdg
