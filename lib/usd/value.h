#pragma once
// A field value of a USD layer, as Sdf stores it: the scalar and array value
// types of attributes (bool, integers, half/float/double, vectors,
// quaternions, matrices, strings, tokens, asset paths) and the metadata
// types (dictionaries, list ops, references, payloads, path and token
// vectors, layer offsets, specifiers, variabilities, variant selections,
// time samples, value blocks). Both readers (usda text, usdc crate) produce
// these and the writer consumes them, so composition and scene_io never
// know which form a layer had.
//
// Numbers are kept as doubles whatever their USD scalar type: every value an
// SDG scene uses (int32, float, half, double, and int64 below 2^53) is exact
// in a double, and one numeric store keeps the type small. `kind` keeps the
// USD type so that writing a layer back gives the same type name.
#include <algorithm>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "core/source_loc.h"

namespace sdg::usd {

// Value kinds, named after Sdf's value types (crate files number them in
// the same order; the readers map between the two).
enum class Kind : uint8_t {
  Empty,  // no value (a field that holds nothing)
  // Numeric scalars (arrays when Value::isArray).
  Bool, UChar, Int, UInt, Int64, UInt64, Half, Float, Double, TimeCode,
  Vec2i, Vec2h, Vec2f, Vec2d,
  Vec3i, Vec3h, Vec3f, Vec3d,
  Vec4i, Vec4h, Vec4f, Vec4d,
  Quath, Quatf, Quatd,  // stored (real, i, j, k) — crate and usda order differ; readers normalise
  Matrix2d, Matrix3d, Matrix4d,  // row-major, as USD writes them
  // Text scalars (arrays when Value::isArray).
  String, Token, AssetPath,
  // Metadata.
  Dictionary,
  TokenListOp, StringListOp, PathListOp, ReferenceListOp, PayloadListOp,
  IntListOp, Int64ListOp, UIntListOp, UInt64ListOp,
  PathVector, TokenVector, StringVector, DoubleVector, LayerOffsetVector,
  Specifier, Permission, Variability,
  VariantSelectionMap,
  TimeSamples,
  Reference, Payload,  // single ones (a payload field of crate 0.8 holds one)
  ValueBlock,          // `None` in usda: an authored "no value"
  Unsupported,         // a type this reader keeps but does not interpret (its name in `strings[0]`)
};

const char* kindName(Kind kind);            // "float3", "token", "dictionary", ...
int componentCount(Kind kind);              // 1 for scalars, 2..4 for vectors, 4 quats, 4/9/16 matrices; 0 non-numeric
bool isNumeric(Kind kind);
Kind componentKind(Kind kind);  // the scalar kind of each component (Vec3f -> Float); scalars give themselves
int matrixDimension(Kind kind);  // 2, 3, 4 for the matrices; 0 otherwise
bool isText(Kind kind);

// An attribute's value type: its Kind and whether it is an array. Role
// names map to the Kind of their C++ type ("point3f" and "color3f" are both
// Vec3f, "frame4d" is Matrix4d); the role stays in the spec's typeName.
struct ValueType {
  Kind kind = Kind::Empty;
  bool isArray = false;
};
// Sdf's value type names ("float3", "point3f[]", "texCoord2f", "asset",
// "matrix4d", ...); nullopt for any other name.
std::optional<ValueType> valueTypeForName(std::string_view typeName);
// Every name valueTypeForName accepts, without "[]" (for did-you-mean hints).
const std::vector<std::string>& valueTypeNames();

enum class Specifier : uint8_t { Def, Over, Class };
enum class Variability : uint8_t { Varying, Uniform };
enum class Permission : uint8_t { Public, Private };

struct LayerOffset {
  double offset = 0.0;
  double scale = 1.0;
  bool operator==(const LayerOffset&) const = default;
};

class Value;
using Dictionary = std::map<std::string, Value>;

// A reference or a payload: an asset path ("" = internal), a prim path in
// it ("" = the layer's defaultPrim), a layer offset, custom data.
struct Reference {
  std::string assetPath;
  std::string primPath;
  LayerOffset offset;
  std::shared_ptr<Dictionary> customData;  // null when none is authored
  // Where the arc was written (usda: its @asset@ or <path>; unknown for
  // crate layers). Not part of the reference's identity.
  SourceLoc loc;
};
bool operator==(const Reference& a, const Reference& b);

// Sdf's list op: either an explicit list, or edits to the weaker opinion's
// list (delete, then prepend and append; `added` and `ordered` are the old
// forms, kept for writing back).
template <class T>
struct ListOp {
  bool isExplicit = false;
  std::vector<T> explicitItems, addedItems, prependedItems, appendedItems, deletedItems, orderedItems;

  // The list after applying this op to `weaker` (USD's SdfListOp::ApplyOperations
  // semantics: explicit replaces; otherwise delete, then prepend at the front
  // and append at the back, each item appearing once).
  std::vector<T> applyTo(const std::vector<T>& weaker) const;
  bool empty() const {
    return !isExplicit && addedItems.empty() && prependedItems.empty() && appendedItems.empty() &&
           deletedItems.empty() && orderedItems.empty();
  }
  bool operator==(const ListOp&) const = default;
};

struct TimeSamples;

class Value {
 public:
  Kind kind = Kind::Empty;
  bool isArray = false;
  // Numeric kinds: componentCount(kind) numbers per element, elements in order.
  std::vector<double> numbers;
  // String, Token, AssetPath (one per element), PathVector, TokenVector,
  // StringVector, Unsupported (the type name).
  std::vector<std::string> strings;
  // Specifier, Variability, Permission: the enum's value.
  int enumValue = 0;
  // Dictionary and VariantSelectionMap (string values as Kind::String).
  std::shared_ptr<Dictionary> dictionary;
  std::shared_ptr<ListOp<std::string>> textListOp;   // Token/String/Path list ops
  std::shared_ptr<ListOp<int64_t>> intListOp;        // the integer list ops
  std::shared_ptr<ListOp<Reference>> referenceListOp;  // Reference and Payload list ops
  std::shared_ptr<std::vector<Reference>> references;  // Reference / Payload: exactly one element
  std::shared_ptr<std::vector<LayerOffset>> layerOffsets;
  std::shared_ptr<TimeSamples> timeSamples;

  bool empty() const { return kind == Kind::Empty; }
  size_t elementCount() const;  // 1 for a scalar; array length otherwise

  // Builders for the common cases.
  static Value scalar(Kind kind, std::vector<double> components);
  static Value array(Kind kind, std::vector<double> flatComponents);
  static Value text(Kind kind, std::string s);  // String, Token or AssetPath
  static Value textArray(Kind kind, std::vector<std::string> items);
  static Value specifier(Specifier s);
  static Value variability(Variability v);
  static Value dict(Dictionary d);
  static Value block();

  // Accessors that throw std::invalid_argument naming the expected kind.
  double asDouble() const;                   // a numeric scalar of one component
  bool asBool() const;
  const std::string& asString() const;       // String, Token or AssetPath scalar
  const std::vector<std::string>& asStrings() const;
};
// Deep equality (the shared parts compared by content).
bool operator==(const Value& a, const Value& b);

struct TimeSamples {
  std::vector<double> times;  // ascending
  std::vector<Value> values;  // one per time (a ValueBlock where blocked)
  // The value held at `time` (USD: the sample at or before it, the first
  // before the first sample; no interpolation here — callers that need
  // linear interpolation of numbers do it themselves).
  const Value* heldAt(double time) const;
  bool operator==(const TimeSamples&) const = default;
};

// The identity of a list-op item, for applyTo's lookups (a reference's
// custom data is not part of it).
inline const std::string& listOpKey(const std::string& item) { return item; }
inline int64_t listOpKey(int64_t item) { return item; }
std::string listOpKey(const Reference& item);

// Sdf's ApplyOperations, in O(n) expected time however long the lists (a
// hostile layer may write a million items).
template <class T>
std::vector<T> ListOp<T>::applyTo(const std::vector<T>& weaker) const {
  using Key = std::decay_t<decltype(listOpKey(std::declval<const T&>()))>;
  auto unique = [](const std::vector<T>& items, std::unordered_set<Key>& seen, std::vector<T>& out) {
    for (const T& item : items)
      if (seen.insert(listOpKey(item)).second) out.push_back(item);
  };
  auto removeAll = [](std::vector<T>& items, const std::unordered_set<Key>& keys) {
    items.erase(std::remove_if(items.begin(), items.end(), [&](const T& item) { return keys.count(listOpKey(item)) > 0; }),
                items.end());
  };
  std::vector<T> result;
  std::unordered_set<Key> present;
  if (isExplicit) {
    unique(explicitItems, present, result);
    return result;
  }
  unique(weaker, present, result);
  if (!deletedItems.empty()) {
    std::unordered_set<Key> gone;
    for (const T& item : deletedItems) gone.insert(listOpKey(item));
    removeAll(result, gone);
    for (const Key& key : gone) present.erase(key);
  }
  for (const T& item : addedItems)
    if (present.insert(listOpKey(item)).second) result.push_back(item);
  if (!prependedItems.empty()) {  // to the front in their order, the first of repeated items counting
    std::vector<T> front;
    std::unordered_set<Key> keys;
    unique(prependedItems, keys, front);
    removeAll(result, keys);
    front.insert(front.end(), result.begin(), result.end());
    result = std::move(front);
    present.insert(keys.begin(), keys.end());
  }
  if (!appendedItems.empty()) {  // to the back in their order, the last of repeated items counting
    std::vector<T> back;
    std::unordered_set<Key> keys;
    for (auto it = appendedItems.rbegin(); it != appendedItems.rend(); ++it)
      if (keys.insert(listOpKey(*it)).second) back.push_back(*it);
    std::reverse(back.begin(), back.end());
    removeAll(result, keys);
    result.insert(result.end(), back.begin(), back.end());
    present.insert(keys.begin(), keys.end());
  }
  // The old `reorder` form: the listed items that are present take, among
  // the positions they occupy, the order given.
  if (!orderedItems.empty()) {
    std::unordered_map<Key, size_t> rank;
    for (size_t i = 0; i < orderedItems.size(); ++i) rank.emplace(listOpKey(orderedItems[i]), i);
    std::vector<size_t> slots;
    std::vector<T> placed;
    for (size_t i = 0; i < result.size(); ++i)
      if (rank.count(listOpKey(result[i]))) {
        slots.push_back(i);
        placed.push_back(result[i]);
      }
    std::stable_sort(placed.begin(), placed.end(),
                     [&](const T& a, const T& b) { return rank.at(listOpKey(a)) < rank.at(listOpKey(b)); });
    for (size_t i = 0; i < slots.size(); ++i) result[slots[i]] = placed[i];
  }
  return result;
}

extern template struct ListOp<std::string>;
extern template struct ListOp<int64_t>;
extern template struct ListOp<Reference>;

}  // namespace sdg::usd
