#include "usd/crate_values.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include "usd/integer_coding.h"

namespace sdg::usd {

namespace {

// Below this many elements crate arrays are never compressed, whatever the
// rep's compressed bit says.
constexpr uint64_t kMinCompressedArraySize = 16;
// What one decoded value costs at least, charged against the output budget.
constexpr uint64_t kValueCost = 64;

enum class Scalar : uint8_t { Bool, U8, I32, U32, I64, U64, F16, F32, F64 };
enum class Shape : uint8_t { Single, Vector, Matrix, Quat };

struct NumericType {
  Kind kind;
  Scalar scalar;
  uint8_t components;
  Shape shape;
};

size_t scalarBytes(Scalar s) {
  switch (s) {
    case Scalar::Bool:
    case Scalar::U8: return 1;
    case Scalar::F16: return 2;
    case Scalar::I32:
    case Scalar::U32:
    case Scalar::F32: return 4;
    default: return 8;
  }
}

// The numeric crate types (nullptr for the others).
const NumericType* numericType(uint8_t type) {
  using T = CrateType;
  static const NumericType kBool{Kind::Bool, Scalar::Bool, 1, Shape::Single},
      kUChar{Kind::UChar, Scalar::U8, 1, Shape::Single}, kInt{Kind::Int, Scalar::I32, 1, Shape::Single},
      kUInt{Kind::UInt, Scalar::U32, 1, Shape::Single}, kInt64{Kind::Int64, Scalar::I64, 1, Shape::Single},
      kUInt64{Kind::UInt64, Scalar::U64, 1, Shape::Single}, kHalf{Kind::Half, Scalar::F16, 1, Shape::Single},
      kFloat{Kind::Float, Scalar::F32, 1, Shape::Single}, kDouble{Kind::Double, Scalar::F64, 1, Shape::Single},
      kTimeCode{Kind::TimeCode, Scalar::F64, 1, Shape::Single},
      kM2{Kind::Matrix2d, Scalar::F64, 4, Shape::Matrix}, kM3{Kind::Matrix3d, Scalar::F64, 9, Shape::Matrix},
      kM4{Kind::Matrix4d, Scalar::F64, 16, Shape::Matrix}, kQd{Kind::Quatd, Scalar::F64, 4, Shape::Quat},
      kQf{Kind::Quatf, Scalar::F32, 4, Shape::Quat}, kQh{Kind::Quath, Scalar::F16, 4, Shape::Quat},
      k2d{Kind::Vec2d, Scalar::F64, 2, Shape::Vector}, k2f{Kind::Vec2f, Scalar::F32, 2, Shape::Vector},
      k2h{Kind::Vec2h, Scalar::F16, 2, Shape::Vector}, k2i{Kind::Vec2i, Scalar::I32, 2, Shape::Vector},
      k3d{Kind::Vec3d, Scalar::F64, 3, Shape::Vector}, k3f{Kind::Vec3f, Scalar::F32, 3, Shape::Vector},
      k3h{Kind::Vec3h, Scalar::F16, 3, Shape::Vector}, k3i{Kind::Vec3i, Scalar::I32, 3, Shape::Vector},
      k4d{Kind::Vec4d, Scalar::F64, 4, Shape::Vector}, k4f{Kind::Vec4f, Scalar::F32, 4, Shape::Vector},
      k4h{Kind::Vec4h, Scalar::F16, 4, Shape::Vector}, k4i{Kind::Vec4i, Scalar::I32, 4, Shape::Vector};
  switch (T(type)) {
    case T::Bool: return &kBool;
    case T::UChar: return &kUChar;
    case T::Int: return &kInt;
    case T::UInt: return &kUInt;
    case T::Int64: return &kInt64;
    case T::UInt64: return &kUInt64;
    case T::Half: return &kHalf;
    case T::Float: return &kFloat;
    case T::Double: return &kDouble;
    case T::TimeCode: return &kTimeCode;
    case T::Matrix2d: return &kM2;
    case T::Matrix3d: return &kM3;
    case T::Matrix4d: return &kM4;
    case T::Quatd: return &kQd;
    case T::Quatf: return &kQf;
    case T::Quath: return &kQh;
    case T::Vec2d: return &k2d;
    case T::Vec2f: return &k2f;
    case T::Vec2h: return &k2h;
    case T::Vec2i: return &k2i;
    case T::Vec3d: return &k3d;
    case T::Vec3f: return &k3f;
    case T::Vec3h: return &k3h;
    case T::Vec3i: return &k3i;
    case T::Vec4d: return &k4d;
    case T::Vec4f: return &k4f;
    case T::Vec4h: return &k4h;
    case T::Vec4i: return &k4i;
    default: return nullptr;
  }
}

float halfToFloat(uint16_t h) {
  const uint32_t sign = uint32_t(h & 0x8000) << 16;
  const uint32_t exponent = (h >> 10) & 0x1f;
  const uint32_t mantissa = h & 0x3ff;
  if (exponent == 0) {  // zero or subnormal: mantissa * 2^-24
    float magnitude = std::ldexp(float(mantissa), -24);
    return sign ? -magnitude : magnitude;
  }
  uint32_t bits = exponent == 31 ? (sign | 0x7f800000u | (mantissa << 13))
                                 : (sign | ((exponent + 112) << 23) | (mantissa << 13));
  return std::bit_cast<float>(bits);
}

template <class T>
T load(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

// Appends `count` scalars of type `s` stored contiguously at `p`.
void appendScalars(Scalar s, const uint8_t* p, size_t count, std::vector<double>& out) {
  if (count == 0) return;  // (an empty span's data may be null)
  size_t at = out.size();
  out.resize(at + count);
  double* o = out.data() + at;
  switch (s) {
    case Scalar::Bool:
      for (size_t i = 0; i < count; ++i) o[i] = p[i] ? 1.0 : 0.0;
      break;
    case Scalar::U8:
      for (size_t i = 0; i < count; ++i) o[i] = p[i];
      break;
    case Scalar::I32:
      for (size_t i = 0; i < count; ++i) o[i] = load<int32_t>(p + 4 * i);
      break;
    case Scalar::U32:
      for (size_t i = 0; i < count; ++i) o[i] = load<uint32_t>(p + 4 * i);
      break;
    case Scalar::I64:
      for (size_t i = 0; i < count; ++i) o[i] = double(load<int64_t>(p + 8 * i));
      break;
    case Scalar::U64:
      for (size_t i = 0; i < count; ++i) o[i] = double(load<uint64_t>(p + 8 * i));
      break;
    case Scalar::F16:
      for (size_t i = 0; i < count; ++i) o[i] = halfToFloat(load<uint16_t>(p + 2 * i));
      break;
    case Scalar::F32:
      for (size_t i = 0; i < count; ++i) o[i] = load<float>(p + 4 * i);
      break;
    case Scalar::F64:
      std::memcpy(o, p, count * 8);
      break;
  }
}

// Crate files store quaternions as (i, j, k, real); Value keeps (real, i, j, k).
void quatsToRealFirst(std::vector<double>& numbers) {
  for (size_t q = 0; q + 4 <= numbers.size(); q += 4) std::rotate(&numbers[q], &numbers[q + 3], &numbers[q + 4]);
}

Value numericValue(Kind kind, bool isArray, std::vector<double> numbers) {
  Value v;
  v.kind = kind;
  v.isArray = isArray;
  v.numbers = std::move(numbers);
  return v;
}

Value unsupported(uint8_t type, std::vector<std::string> extra = {}) {
  Value v;
  v.kind = Kind::Unsupported;
  v.enumValue = type;
  v.strings.reserve(extra.size() + 1);
  v.strings.push_back(crateTypeName(type));
  for (auto& s : extra) v.strings.push_back(std::move(s));
  return v;
}

// List op header bits, in the order their item lists follow the header.
constexpr uint8_t kListOpExplicit = 1 << 0;
struct ListOpPart {
  uint8_t bit;
  int slot;  // explicit, added, prepended, appended, deleted, ordered
};
constexpr ListOpPart kListOpParts[] = {{1 << 1, 0}, {1 << 2, 1}, {1 << 5, 2}, {1 << 6, 3}, {1 << 3, 4}, {1 << 4, 5}};

template <class T>
std::vector<T>& listOpSlot(ListOp<T>& op, int slot) {
  switch (slot) {
    case 0: return op.explicitItems;
    case 1: return op.addedItems;
    case 2: return op.prependedItems;
    case 3: return op.appendedItems;
    case 4: return op.deletedItems;
    default: return op.orderedItems;
  }
}

// Reads a list op whose items `readItem` reads (each at least `minItemBytes`).
template <class T, class ReadItem>
ListOp<T> readListOp(ByteCursor& in, uint64_t minItemBytes, ReadItem readItem) {
  ListOp<T> op;
  auto header = in.read<uint8_t>("list op header");
  op.isExplicit = header & kListOpExplicit;
  for (const auto& part : kListOpParts) {
    if (!(header & part.bit)) continue;
    auto& items = listOpSlot(op, part.slot);
    auto count = in.readCount("list op items", minItemBytes);
    items.reserve(count);
    for (uint64_t i = 0; i < count; ++i) items.push_back(readItem());
  }
  return op;
}

}  // namespace

CrateValueReader::CrateValueReader(const CrateFile& crate)
    : crate_(crate), budget_(crate.limits().maxDecompressedBytes) {}

void CrateValueReader::charge(uint64_t bytes) {
  if (bytes > budget_)
    throw CodingError("the decoded values exceed the limit of " +
                      std::to_string(crate_.limits().maxDecompressedBytes) + " bytes");
  budget_ -= bytes;
}

Value CrateValueReader::textValue(Kind kind, std::string s) {
  charge(s.size());
  Value v;
  v.kind = kind;
  v.strings.push_back(std::move(s));
  return v;
}

ByteCursor CrateValueReader::at(uint64_t offset) {
  ByteCursor in(crate_.bytes());
  in.seek(offset);
  return in;
}

uint64_t CrateValueReader::readArraySize(ByteCursor& in) {
  const auto version = crate_.version();
  if (!version.atLeast(0, 5)) in.read<uint32_t>("array rank");  // files before 0.5.0 store a rank of 1
  uint64_t count = version.atLeast(0, 7) ? in.read<uint64_t>("array size") : in.read<uint32_t>("array size");
  if (count > crate_.limits().maxArrayElements)
    throw CodingError("an array of " + std::to_string(count) + " elements exceeds the limit of " +
                      std::to_string(crate_.limits().maxArrayElements));
  return count;
}

Value CrateValueReader::unpack(ValueRep rep, uint32_t depth) {
  if (depth > crate_.limits().maxNesting)
    throw CodingError("values nest deeper than " + std::to_string(crate_.limits().maxNesting) + " levels");
  charge(kValueCost);
  const uint8_t type = rep.type();
  using T = CrateType;
  if (numericType(type))
    return rep.isArray() ? unpackNumericArray(rep, type) : unpackNumeric(rep, type);

  switch (T(type)) {
    case T::String:
      return rep.isArray() ? unpackTextArray(rep, Kind::String) : textValue(Kind::String, crate_.string(rep.payload32()));
    case T::Token:
      return rep.isArray() ? unpackTextArray(rep, Kind::Token) : textValue(Kind::Token, crate_.token(rep.payload32()));
    case T::AssetPath:  // a scalar holds a token index, array elements string indexes
      return rep.isArray() ? unpackTextArray(rep, Kind::AssetPath)
                           : textValue(Kind::AssetPath, crate_.token(rep.payload32()));
    case T::Specifier:
    case T::Permission:
    case T::Variability: {
      Value v;
      v.kind = T(type) == T::Specifier ? Kind::Specifier : T(type) == T::Permission ? Kind::Permission
                                                                                      : Kind::Variability;
      uint32_t raw = rep.payload32();
      if (v.kind == Kind::Variability && raw == 2) raw = 1;  // the legacy "config" variability reads as uniform
      uint32_t maxValue = v.kind == Kind::Specifier ? 2 : 1;
      if (raw > maxValue)
        throw CodingError(std::string(crateTypeName(type)) + " value " + std::to_string(raw) + " is out of range");
      v.enumValue = int(raw);
      return v;
    }
    case T::ValueBlock: {
      Value v;
      v.kind = Kind::ValueBlock;
      return v;
    }
    default: break;
  }

  // Everything else is stored out of line, except values the writer could
  // inline as "empty" (a dictionary with no entries; other types never are).
  if (rep.isInlined()) {
    Value v;
    switch (T(type)) {
      case T::Dictionary:
        v.kind = Kind::Dictionary;
        v.dictionary = std::make_shared<Dictionary>();
        return v;
      default: return unsupported(type);
    }
  }

  if (type > uint8_t(T::Relocates) || T(type) == T::UnregisteredValue || T(type) == T::UnregisteredValueListOp ||
      T(type) == T::Invalid)
    return unsupported(type);  // its data is not looked at: a newer type's layout is unknown

  // Values that hold their data by shared pointer are decoded once per rep:
  // fields share reps, and a hostile file can make dictionaries share
  // entries level after level, which would otherwise cost 2^depth.
  switch (T(type)) {
    case T::Dictionary:
    case T::VariantSelectionMap:
    case T::TokenListOp:
    case T::StringListOp:
    case T::PathListOp:
    case T::ReferenceListOp:
    case T::PayloadListOp:
    case T::IntListOp:
    case T::UIntListOp:
    case T::Int64ListOp:
    case T::UInt64ListOp:
    case T::Payload:
    case T::LayerOffsetVector:
    case T::TimeSamples: {
      if (auto it = shared_.find(rep.bits); it != shared_.end()) return it->second;
      Value v = unpackOutOfLine(rep, depth);
      shared_.emplace(rep.bits, v);
      return v;
    }
    default: return unpackOutOfLine(rep, depth);
  }
}

Value CrateValueReader::unpackOutOfLine(ValueRep rep, uint32_t depth) {
  const uint8_t type = rep.type();
  using T = CrateType;
  auto textVector = [this](Kind kind, ByteCursor& in, auto lookup) {
    Value v;
    v.kind = kind;
    auto count = in.readCount("vector size", 4);
    v.strings.reserve(count);
    for (uint64_t i = 0; i < count; ++i) {
      v.strings.push_back(lookup(in.read<uint32_t>("vector item")));
      charge(v.strings.back().size() + 32);
    }
    return v;
  };
  auto tokenAt = [this](uint32_t i) { return crate_.token(i); };
  auto stringAt = [this](uint32_t i) { return crate_.string(i); };
  auto pathAt = [this](uint32_t i) { return crate_.path(i); };

  ByteCursor in = at(rep.payload());
  Value v;
  switch (T(type)) {
    case T::Dictionary:
      v.kind = Kind::Dictionary;
      v.dictionary = std::make_shared<Dictionary>(readDictionary(in, depth));
      return v;
    case T::VariantSelectionMap: {
      v.kind = Kind::VariantSelectionMap;
      v.dictionary = std::make_shared<Dictionary>();
      auto count = in.readCount("variant selections", 8);
      for (uint64_t i = 0; i < count; ++i) {
        std::string key = crate_.string(in.read<uint32_t>("variant set name"));
        std::string value = crate_.string(in.read<uint32_t>("variant selection"));
        charge(key.size() + value.size() + kValueCost);
        (*v.dictionary)[std::move(key)] = textValue(Kind::String, std::move(value));
      }
      return v;
    }
    case T::TokenListOp:
    case T::StringListOp:
    case T::PathListOp: {
      v.kind = T(type) == T::TokenListOp ? Kind::TokenListOp : T(type) == T::StringListOp ? Kind::StringListOp
                                                                                           : Kind::PathListOp;
      auto readItem = [&]() -> std::string {
        uint32_t i = in.read<uint32_t>("list op item");
        std::string s = v.kind == Kind::TokenListOp ? crate_.token(i) : v.kind == Kind::StringListOp ? crate_.string(i)
                                                                                                     : crate_.path(i);
        charge(s.size() + 32);
        return s;
      };
      v.textListOp = std::make_shared<ListOp<std::string>>(readListOp<std::string>(in, 4, readItem));
      return v;
    }
    case T::IntListOp:
    case T::UIntListOp:
    case T::Int64ListOp:
    case T::UInt64ListOp: {
      const T t = T(type);
      v.kind = t == T::IntListOp ? Kind::IntListOp : t == T::UIntListOp ? Kind::UIntListOp
                                 : t == T::Int64ListOp ? Kind::Int64ListOp : Kind::UInt64ListOp;
      const bool wide = t == T::Int64ListOp || t == T::UInt64ListOp;
      auto readItem = [&]() -> int64_t {
        charge(8);
        switch (t) {
          case T::IntListOp: return in.read<int32_t>("list op item");
          case T::UIntListOp: return in.read<uint32_t>("list op item");
          default: return in.read<int64_t>("list op item");  // uint64 beyond 2^63 wraps, as Value keeps int64
        }
      };
      v.intListOp = std::make_shared<ListOp<int64_t>>(readListOp<int64_t>(in, wide ? 8 : 4, readItem));
      return v;
    }
    case T::ReferenceListOp:
    case T::PayloadListOp: {
      const bool isPayload = T(type) == T::PayloadListOp;
      v.kind = isPayload ? Kind::PayloadListOp : Kind::ReferenceListOp;
      auto readItem = [&]() { return readReference(in, depth, isPayload); };
      v.referenceListOp = std::make_shared<ListOp<Reference>>(readListOp<Reference>(in, 8, readItem));
      return v;
    }
    case T::Payload:
      v.kind = Kind::Payload;
      v.references = std::make_shared<std::vector<Reference>>(1, readReference(in, depth, true));
      return v;
    case T::PathVector: return textVector(Kind::PathVector, in, pathAt);
    case T::TokenVector: return textVector(Kind::TokenVector, in, tokenAt);
    case T::StringVector: return textVector(Kind::StringVector, in, stringAt);
    case T::DoubleVector: {
      auto count = in.readCount("double vector size", 8);
      charge(count * 8);
      std::vector<double> numbers;
      appendScalars(Scalar::F64, in.take(count * 8, "doubles").data(), count, numbers);
      return numericValue(Kind::DoubleVector, false, std::move(numbers));
    }
    case T::LayerOffsetVector: {
      auto count = in.readCount("layer offsets", 16);
      charge(count * 16);
      v.kind = Kind::LayerOffsetVector;
      v.layerOffsets = std::make_shared<std::vector<LayerOffset>>(count);
      for (auto& offset : *v.layerOffsets) {
        offset.offset = in.read<double>("layer offset");
        offset.scale = in.read<double>("layer scale");
      }
      return v;
    }
    case T::TimeSamples: return readTimeSamples(in, depth);
    case T::Value: return readVtValue(in, depth + 1);
    case T::PathExpression: {
      if (rep.isArray()) {
        auto count = rep.payload() == 0 ? 0 : readArraySize(in);  // offset 0: an empty array
        if (count > in.remaining() / 4) throw CodingError("path expression array overruns the file");
        std::vector<std::string> texts;
        for (uint64_t i = 0; i < count; ++i) {
          texts.push_back(crate_.string(in.read<uint32_t>("path expression")));
          charge(texts.back().size() + 32);
        }
        Value u = unsupported(type, std::move(texts));
        u.isArray = true;
        return u;
      }
      std::string text = crate_.string(in.read<uint32_t>("path expression"));
      charge(text.size());
      return unsupported(type, {std::move(text)});
    }
    case T::Relocates: {
      auto count = in.readCount("relocates", 8);
      std::vector<std::string> paths;
      for (uint64_t i = 0; i < 2 * count; ++i) {
        paths.push_back(crate_.path(in.read<uint32_t>("relocate path")));
        charge(paths.back().size() + 32);
      }
      return unsupported(type, std::move(paths));
    }
    default: return unsupported(type);
  }
}

Value CrateValueReader::unpackNumeric(ValueRep rep, uint8_t type) {
  const NumericType& t = *numericType(type);
  const size_t scalarSize = scalarBytes(t.scalar);
  std::vector<double> numbers;
  numbers.reserve(t.components);
  const uint32_t payload = rep.payload32();
  const auto* payloadBytes = reinterpret_cast<const uint8_t*>(&payload);
  if (t.components == 1 && scalarSize <= 4) {
    // Always inlined: the value's bytes are the payload's low bytes.
    appendScalars(t.scalar, payloadBytes, 1, numbers);
  } else if (rep.isInlined()) {
    switch (t.shape) {
      case Shape::Single:  // 64-bit values that fit 32 bits: int32, uint32 or float
        if (t.kind == Kind::Int64) numbers.push_back(int32_t(payload));
        else if (t.kind == Kind::UInt64) numbers.push_back(payload);
        else if (t.kind == Kind::Double) numbers.push_back(std::bit_cast<float>(payload));
        else numbers.push_back(0.0);  // USD never inlines a TimeCode; its default is 0
        break;
      case Shape::Vector:  // every component an int8
        for (int i = 0; i < t.components; ++i) numbers.push_back(int8_t(payloadBytes[i]));
        break;
      case Shape::Matrix: {  // a diagonal matrix of int8s
        int dim = t.components == 4 ? 2 : t.components == 9 ? 3 : 4;
        numbers.assign(t.components, 0.0);
        for (int i = 0; i < dim; ++i) numbers[size_t(i * dim + i)] = int8_t(payloadBytes[i]);
        break;
      }
      case Shape::Quat:  // USD never inlines quaternions: a default (zero) one
        numbers.assign(4, 0.0);
        break;
    }
  } else {
    ByteCursor in = at(rep.payload());
    appendScalars(t.scalar, in.take(scalarSize * t.components, crateTypeName(type)).data(), t.components, numbers);
    if (t.shape == Shape::Quat) quatsToRealFirst(numbers);
  }
  return numericValue(t.kind, false, std::move(numbers));
}

Value CrateValueReader::unpackNumericArray(ValueRep rep, uint8_t type) {
  const NumericType& t = *numericType(type);
  if (rep.payload() == 0) return numericValue(t.kind, true, {});  // an empty array
  ByteCursor in = at(rep.payload());
  const uint64_t count = readArraySize(in);
  const uint64_t values = count * t.components;
  charge(values * sizeof(double));
  const auto version = crate_.version();
  const bool isInteger = t.components == 1 && (t.scalar == Scalar::I32 || t.scalar == Scalar::U32 ||
                                                t.scalar == Scalar::I64 || t.scalar == Scalar::U64);
  const bool isFloat = t.components == 1 && (t.scalar == Scalar::F16 || t.scalar == Scalar::F32 ||
                                             t.scalar == Scalar::F64) && t.kind != Kind::TimeCode;
  const bool compressed = rep.isCompressed() && count >= kMinCompressedArraySize &&
                          ((isInteger && version.atLeast(0, 5)) || (isFloat && version.atLeast(0, 6)));
  std::vector<double> numbers;
  if (!compressed) {
    const size_t elementBytes = scalarBytes(t.scalar) * t.components;
    if (count > in.remaining() / elementBytes)
      throw CodingError(std::string(crateTypeName(type)) + " array of " + std::to_string(count) +
                        " elements overruns the file");
    numbers.reserve(values);
    appendScalars(t.scalar, in.take(count * elementBytes, "array").data(), values, numbers);
    if (t.shape == Shape::Quat) quatsToRealFirst(numbers);
    return numericValue(t.kind, true, std::move(numbers));
  }
  const uint64_t maxCount = crate_.limits().maxArrayElements;
  if (isInteger) {
    auto copy = [&numbers](const auto& ints) { numbers.assign(ints.begin(), ints.end()); };
    switch (t.scalar) {
      case Scalar::I32: copy(readCompressedIntegers<int32_t>(in, count, maxCount, "compressed ints")); break;
      case Scalar::U32: copy(readCompressedIntegers<uint32_t>(in, count, maxCount, "compressed ints")); break;
      case Scalar::I64: copy(readCompressedIntegers<int64_t>(in, count, maxCount, "compressed ints")); break;
      default: copy(readCompressedIntegers<uint64_t>(in, count, maxCount, "compressed ints")); break;
    }
    return numericValue(t.kind, true, std::move(numbers));
  }
  auto code = in.read<char>("float array code");
  if (code == 'i') {  // every value an integer
    auto ints = readCompressedIntegers<int32_t>(in, count, maxCount, "float array as ints");
    numbers.assign(ints.begin(), ints.end());
  } else if (code == 't') {  // a lookup table and an index per value
    const size_t scalarSize = scalarBytes(t.scalar);
    auto tableSize = in.read<uint32_t>("lookup table size");
    if (tableSize > in.remaining() / scalarSize)
      throw CodingError("lookup table of " + std::to_string(tableSize) + " values overruns the file");
    std::vector<double> table;
    appendScalars(t.scalar, in.take(tableSize * scalarSize, "lookup table").data(), tableSize, table);
    auto indexes = readCompressedIntegers<uint32_t>(in, count, maxCount, "lookup table indexes");
    numbers.resize(count);
    for (size_t i = 0; i < count; ++i) {
      if (indexes[i] >= tableSize)
        throw CodingError("lookup table index " + std::to_string(indexes[i]) + " is past the table's " +
                          std::to_string(tableSize) + " values");
      numbers[i] = table[indexes[i]];
    }
  } else {
    throw CodingError("compressed float array has unknown code " + std::to_string(int(code)));
  }
  return numericValue(t.kind, true, std::move(numbers));
}

Value CrateValueReader::unpackTextArray(ValueRep rep, Kind kind) {
  Value v;
  v.kind = kind;
  v.isArray = true;
  if (rep.payload() == 0) return v;
  ByteCursor in = at(rep.payload());
  auto count = readArraySize(in);
  if (count > in.remaining() / 4) throw CodingError("text array of " + std::to_string(count) + " overruns the file");
  v.strings.reserve(count);
  for (uint64_t i = 0; i < count; ++i) {
    uint32_t index = in.read<uint32_t>("text array item");
    v.strings.push_back(kind == Kind::Token ? crate_.token(index) : crate_.string(index));
    charge(v.strings.back().size() + 32);
  }
  return v;
}

// A value nested in another (a dictionary entry, a time sample): an offset
// from here to its rep, then the rep.
Value CrateValueReader::readVtValue(ByteCursor& in, uint32_t depth) {
  const uint64_t start = in.tell();
  auto offset = in.read<int64_t>("nested value offset");
  in.seek(start + uint64_t(offset));
  return unpack(ValueRep{in.read<uint64_t>("nested value rep")}, depth);
}

Dictionary CrateValueReader::readDictionary(ByteCursor& in, uint32_t depth) {
  Dictionary dict;
  auto count = in.readCount("dictionary entries", 20);
  for (uint64_t i = 0; i < count; ++i) {
    std::string key = crate_.string(in.read<uint32_t>("dictionary key"));
    charge(key.size());
    dict[std::move(key)] = readVtValue(in, depth + 1);
  }
  return dict;
}

Reference CrateValueReader::readReference(ByteCursor& in, uint32_t depth, bool isPayload) {
  charge(kValueCost);
  Reference r;
  r.assetPath = crate_.string(in.read<uint32_t>("asset path"));
  r.primPath = crate_.path(in.read<uint32_t>("prim path"));
  charge(r.assetPath.size() + r.primPath.size());
  if (!isPayload || crate_.version().atLeast(0, 8)) {  // payloads have layer offsets from 0.8.0
    r.offset.offset = in.read<double>("layer offset");
    r.offset.scale = in.read<double>("layer scale");
  }
  if (!isPayload) {
    Dictionary customData = readDictionary(in, depth + 1);
    if (!customData.empty()) r.customData = std::make_shared<Dictionary>(std::move(customData));
  }
  return r;
}

// Time samples: an offset to the rep of the times (a double vector), then an
// offset to the value count and one rep per time.
Value CrateValueReader::readTimeSamples(ByteCursor& in, uint32_t depth) {
  uint64_t start = in.tell();
  in.seek(start + uint64_t(in.read<int64_t>("time samples offset")));
  ValueRep timesRep{in.read<uint64_t>("sample times rep")};
  start = in.tell();
  in.seek(start + uint64_t(in.read<int64_t>("sample values offset")));
  auto count = in.readCount("sample values", 8);

  Value times = unpack(timesRep, depth + 1);
  if (times.kind != Kind::DoubleVector && !(times.kind == Kind::Double && times.isArray))
    throw CodingError("sample times are a " + std::string(crateTypeName(timesRep.type())) +
                      ", not a double vector");
  if (times.numbers.size() != count)
    throw CodingError(std::to_string(times.numbers.size()) + " sample times but " + std::to_string(count) +
                      " values");
  for (size_t i = 1; i < count; ++i)
    if (!(times.numbers[i - 1] < times.numbers[i]))
      throw CodingError("sample times are not ascending at sample " + std::to_string(i));
  auto samples = std::make_shared<TimeSamples>();
  samples->times = std::move(times.numbers);
  samples->values.reserve(count);
  for (uint64_t i = 0; i < count; ++i)
    samples->values.push_back(unpack(ValueRep{in.read<uint64_t>("sample value rep")}, depth + 1));
  Value v;
  v.kind = Kind::TimeSamples;
  v.timeSamples = std::move(samples);
  return v;
}

}  // namespace sdg::usd
