#include "usd/value.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace sdg::usd {

Kind componentKind(Kind kind) {
  switch (kind) {
    case Kind::Vec2i: case Kind::Vec3i: case Kind::Vec4i: return Kind::Int;
    case Kind::Vec2h: case Kind::Vec3h: case Kind::Vec4h: case Kind::Quath: return Kind::Half;
    case Kind::Vec2f: case Kind::Vec3f: case Kind::Vec4f: case Kind::Quatf: return Kind::Float;
    case Kind::Vec2d: case Kind::Vec3d: case Kind::Vec4d: case Kind::Quatd:
    case Kind::Matrix2d: case Kind::Matrix3d: case Kind::Matrix4d: return Kind::Double;
    default: return kind;
  }
}

int matrixDimension(Kind kind) {
  return kind == Kind::Matrix2d ? 2 : kind == Kind::Matrix3d ? 3 : kind == Kind::Matrix4d ? 4 : 0;
}

namespace {

struct KindInfo {
  Kind kind;
  const char* name;
  int components;  // numbers per element; 0 for non-numeric kinds
};

// One row per Kind, in the enum's order (checked by kindInfo()).
constexpr std::array kKinds = {
    KindInfo{Kind::Empty, "empty", 0},
    KindInfo{Kind::Bool, "bool", 1},
    KindInfo{Kind::UChar, "uchar", 1},
    KindInfo{Kind::Int, "int", 1},
    KindInfo{Kind::UInt, "uint", 1},
    KindInfo{Kind::Int64, "int64", 1},
    KindInfo{Kind::UInt64, "uint64", 1},
    KindInfo{Kind::Half, "half", 1},
    KindInfo{Kind::Float, "float", 1},
    KindInfo{Kind::Double, "double", 1},
    KindInfo{Kind::TimeCode, "timecode", 1},
    KindInfo{Kind::Vec2i, "int2", 2},
    KindInfo{Kind::Vec2h, "half2", 2},
    KindInfo{Kind::Vec2f, "float2", 2},
    KindInfo{Kind::Vec2d, "double2", 2},
    KindInfo{Kind::Vec3i, "int3", 3},
    KindInfo{Kind::Vec3h, "half3", 3},
    KindInfo{Kind::Vec3f, "float3", 3},
    KindInfo{Kind::Vec3d, "double3", 3},
    KindInfo{Kind::Vec4i, "int4", 4},
    KindInfo{Kind::Vec4h, "half4", 4},
    KindInfo{Kind::Vec4f, "float4", 4},
    KindInfo{Kind::Vec4d, "double4", 4},
    KindInfo{Kind::Quath, "quath", 4},
    KindInfo{Kind::Quatf, "quatf", 4},
    KindInfo{Kind::Quatd, "quatd", 4},
    KindInfo{Kind::Matrix2d, "matrix2d", 4},
    KindInfo{Kind::Matrix3d, "matrix3d", 9},
    KindInfo{Kind::Matrix4d, "matrix4d", 16},
    KindInfo{Kind::String, "string", 0},
    KindInfo{Kind::Token, "token", 0},
    KindInfo{Kind::AssetPath, "asset", 0},
    KindInfo{Kind::Dictionary, "dictionary", 0},
    KindInfo{Kind::TokenListOp, "tokenListOp", 0},
    KindInfo{Kind::StringListOp, "stringListOp", 0},
    KindInfo{Kind::PathListOp, "pathListOp", 0},
    KindInfo{Kind::ReferenceListOp, "referenceListOp", 0},
    KindInfo{Kind::PayloadListOp, "payloadListOp", 0},
    KindInfo{Kind::IntListOp, "intListOp", 0},
    KindInfo{Kind::Int64ListOp, "int64ListOp", 0},
    KindInfo{Kind::UIntListOp, "uintListOp", 0},
    KindInfo{Kind::UInt64ListOp, "uint64ListOp", 0},
    KindInfo{Kind::PathVector, "pathVector", 0},
    KindInfo{Kind::TokenVector, "tokenVector", 0},
    KindInfo{Kind::StringVector, "stringVector", 0},
    KindInfo{Kind::DoubleVector, "doubleVector", 0},
    KindInfo{Kind::LayerOffsetVector, "layerOffsetVector", 0},
    KindInfo{Kind::Specifier, "specifier", 0},
    KindInfo{Kind::Permission, "permission", 0},
    KindInfo{Kind::Variability, "variability", 0},
    KindInfo{Kind::VariantSelectionMap, "variantSelectionMap", 0},
    KindInfo{Kind::TimeSamples, "timeSamples", 0},
    KindInfo{Kind::Reference, "reference", 0},
    KindInfo{Kind::Payload, "payload", 0},
    KindInfo{Kind::ValueBlock, "None", 0},
    KindInfo{Kind::Unsupported, "unsupported", 0},
};

constexpr bool kindsInEnumOrder() {
  for (size_t i = 0; i < kKinds.size(); ++i)
    if (static_cast<size_t>(kKinds[i].kind) != i) return false;
  return kKinds.size() == static_cast<size_t>(Kind::Unsupported) + 1;
}
static_assert(kindsInEnumOrder(), "kKinds must list every Kind in the enum's order");

const KindInfo& kindInfo(Kind kind) { return kKinds[static_cast<size_t>(kind)]; }

[[noreturn]] void wrongKind(const Value& v, const char* expected) {
  throw std::invalid_argument(std::string("expected ") + expected + ", found " +
                              (v.isArray ? std::string(kindName(v.kind)) + "[]" : kindName(v.kind)));
}

}  // namespace

const char* kindName(Kind kind) { return kindInfo(kind).name; }
int componentCount(Kind kind) { return kindInfo(kind).components; }
bool isNumeric(Kind kind) { return componentCount(kind) > 0; }
bool isText(Kind kind) { return kind == Kind::String || kind == Kind::Token || kind == Kind::AssetPath; }

namespace {

// Sdf's value type names: the plain ones, then the role names, each stored
// as the Kind of its C++ type.
const std::unordered_map<std::string_view, Kind>& valueTypeTable() {
  static const std::unordered_map<std::string_view, Kind> kTable = [] {
    std::unordered_map<std::string_view, Kind> t;
    for (const KindInfo& info : kKinds)
      if (isNumeric(info.kind) || isText(info.kind)) t.emplace(info.name, info.kind);
    const std::pair<const char*, Kind> roles[] = {
        {"point3h", Kind::Vec3h},    {"point3f", Kind::Vec3f},    {"point3d", Kind::Vec3d},
        {"vector3h", Kind::Vec3h},   {"vector3f", Kind::Vec3f},   {"vector3d", Kind::Vec3d},
        {"normal3h", Kind::Vec3h},   {"normal3f", Kind::Vec3f},   {"normal3d", Kind::Vec3d},
        {"color3h", Kind::Vec3h},    {"color3f", Kind::Vec3f},    {"color3d", Kind::Vec3d},
        {"color4h", Kind::Vec4h},    {"color4f", Kind::Vec4f},    {"color4d", Kind::Vec4d},
        {"texCoord2h", Kind::Vec2h}, {"texCoord2f", Kind::Vec2f}, {"texCoord2d", Kind::Vec2d},
        {"texCoord3h", Kind::Vec3h}, {"texCoord3f", Kind::Vec3f}, {"texCoord3d", Kind::Vec3d},
        {"frame4d", Kind::Matrix4d},
    };
    for (const auto& [name, kind] : roles) t.emplace(name, kind);
    return t;
  }();
  return kTable;
}

}  // namespace

const std::vector<std::string>& valueTypeNames() {
  static const std::vector<std::string> kNames = [] {
    std::vector<std::string> names;
    for (const auto& [name, kind] : valueTypeTable()) names.emplace_back(name);
    std::sort(names.begin(), names.end());
    return names;
  }();
  return kNames;
}

std::optional<ValueType> valueTypeForName(std::string_view typeName) {
  const auto& table = valueTypeTable();
  ValueType result;
  if (typeName.size() > 2 && typeName.substr(typeName.size() - 2) == "[]") {
    result.isArray = true;
    typeName.remove_suffix(2);
  }
  auto it = table.find(typeName);
  if (it == table.end()) return std::nullopt;
  result.kind = it->second;
  return result;
}

// ---- ListOp (applyTo is defined in value.h, for composition's own item types) ----

template struct ListOp<std::string>;
template struct ListOp<int64_t>;
template struct ListOp<Reference>;

std::string listOpKey(const Reference& item) {
  std::string key = item.assetPath;
  key += '\0';
  key += item.primPath;
  key += '\0';
  key.append(reinterpret_cast<const char*>(&item.offset.offset), sizeof(double));
  key.append(reinterpret_cast<const char*>(&item.offset.scale), sizeof(double));
  return key;
}

bool operator==(const Reference& a, const Reference& b) {
  if (a.assetPath != b.assetPath || a.primPath != b.primPath || !(a.offset == b.offset)) return false;
  if (!a.customData || !b.customData) return !a.customData == !b.customData;
  return *a.customData == *b.customData;
}

// ---- Value -----------------------------------------------------------------

size_t Value::elementCount() const {
  if (!isArray) return 1;
  if (isNumeric(kind)) return numbers.size() / static_cast<size_t>(componentCount(kind));
  return strings.size();
}

Value Value::scalar(Kind kind, std::vector<double> components) {
  if (!isNumeric(kind) || components.size() != static_cast<size_t>(componentCount(kind)))
    throw std::invalid_argument(std::string("Value::scalar: ") + kindName(kind) + " takes " +
                                std::to_string(componentCount(kind)) + " numbers, given " +
                                std::to_string(components.size()));
  Value v;
  v.kind = kind;
  v.numbers = std::move(components);
  return v;
}

Value Value::array(Kind kind, std::vector<double> flatComponents) {
  if (!isNumeric(kind) || flatComponents.size() % static_cast<size_t>(componentCount(kind)) != 0)
    throw std::invalid_argument(std::string("Value::array: ") + std::to_string(flatComponents.size()) +
                                " numbers do not make whole " + kindName(kind) + " elements");
  Value v;
  v.kind = kind;
  v.isArray = true;
  v.numbers = std::move(flatComponents);
  return v;
}

Value Value::text(Kind kind, std::string s) {
  if (!isText(kind)) throw std::invalid_argument(std::string("Value::text: ") + kindName(kind) + " is not a text kind");
  Value v;
  v.kind = kind;
  v.strings.push_back(std::move(s));
  return v;
}

Value Value::textArray(Kind kind, std::vector<std::string> items) {
  bool vectorKind = kind == Kind::PathVector || kind == Kind::TokenVector || kind == Kind::StringVector;
  if (!isText(kind) && !vectorKind)
    throw std::invalid_argument(std::string("Value::textArray: ") + kindName(kind) + " is not a text kind");
  Value v;
  v.kind = kind;
  v.isArray = isText(kind);
  v.strings = std::move(items);
  return v;
}

Value Value::specifier(Specifier s) {
  Value v;
  v.kind = Kind::Specifier;
  v.enumValue = static_cast<int>(s);
  return v;
}

Value Value::variability(Variability var) {
  Value v;
  v.kind = Kind::Variability;
  v.enumValue = static_cast<int>(var);
  return v;
}

Value Value::dict(Dictionary d) {
  Value v;
  v.kind = Kind::Dictionary;
  v.dictionary = std::make_shared<Dictionary>(std::move(d));
  return v;
}

Value Value::block() {
  Value v;
  v.kind = Kind::ValueBlock;
  return v;
}

double Value::asDouble() const {
  if (isArray || !isNumeric(kind) || numbers.size() != 1) wrongKind(*this, "a number");
  return numbers[0];
}

bool Value::asBool() const {
  if (kind != Kind::Bool || isArray || numbers.size() != 1) wrongKind(*this, "bool");
  return numbers[0] != 0.0;
}

const std::string& Value::asString() const {
  if (!isText(kind) || isArray || strings.size() != 1) wrongKind(*this, "a string, token or asset");
  return strings[0];
}

const std::vector<std::string>& Value::asStrings() const {
  bool vectorKind = kind == Kind::PathVector || kind == Kind::TokenVector || kind == Kind::StringVector ||
                    kind == Kind::Unsupported;
  if (!vectorKind && !(isText(kind) && isArray)) wrongKind(*this, "a list of strings");
  return strings;
}

namespace {
template <class T>
bool samePointee(const std::shared_ptr<T>& a, const std::shared_ptr<T>& b) {
  if (!a || !b) return !a == !b;
  return *a == *b;
}
}  // namespace

bool operator==(const Value& a, const Value& b) {
  return a.kind == b.kind && a.isArray == b.isArray && a.numbers == b.numbers && a.strings == b.strings &&
         a.enumValue == b.enumValue && samePointee(a.dictionary, b.dictionary) &&
         samePointee(a.textListOp, b.textListOp) && samePointee(a.intListOp, b.intListOp) &&
         samePointee(a.referenceListOp, b.referenceListOp) && samePointee(a.references, b.references) &&
         samePointee(a.layerOffsets, b.layerOffsets) && samePointee(a.timeSamples, b.timeSamples);
}

// ---- TimeSamples -------------------------------------------------------------

const Value* TimeSamples::heldAt(double time) const {
  if (times.empty() || values.size() != times.size()) return nullptr;
  // The last sample at or before `time`; the first one before all samples.
  auto after = std::upper_bound(times.begin(), times.end(), time);
  size_t index = after == times.begin() ? 0 : static_cast<size_t>(after - times.begin()) - 1;
  return &values[index];
}

}  // namespace sdg::usd
