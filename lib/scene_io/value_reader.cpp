#include "scene_io/value_reader.h"

#include <charconv>
#include <cmath>
#include <limits>

#include "core/text.h"
#include "stage/xform.h"

namespace sdg {
namespace {

std::string expected(std::string_view what, ValueType type, const RawNode& found) {
  return std::string(what) + ": expected " + std::string(valueTypeShape(type)) + ", found " + found.describe();
}

bool isNonFiniteSpelling(std::string_view s) {
  for (std::string_view n : {".nan", ".NaN", ".NAN", "nan", "NaN", ".inf", ".Inf", ".INF", "+.inf", "-.inf",
                             "-.Inf", "+.Inf", "-.INF", "inf", "-inf", "+inf", "infinity", "-infinity"})
    if (s == n) return true;
  return false;
}

// Plain YAML scalar -> double; nullopt when it is not a number.
std::optional<double> parseDouble(const RawNode& n) {
  if (!n.isScalar() || n.quoted || n.scalar.empty()) return std::nullopt;
  if (isNonFiniteSpelling(n.scalar)) return std::numeric_limits<double>::quiet_NaN();
  const char* begin = n.scalar.data();
  const char* end = begin + n.scalar.size();
  if (*begin == '+') ++begin;
  double v = 0;
  auto [ptr, ec] = std::from_chars(begin, end, v, std::chars_format::general);
  if (ptr != end) return std::nullopt;
  if (ec == std::errc::result_out_of_range) return std::numeric_limits<double>::infinity();
  if (ec != std::errc{}) return std::nullopt;
  return v;
}

struct Reader {
  std::string_view what;
  Diagnostics& diag;

  std::optional<double> number(const RawNode& n, ValueType type, bool single) {
    std::optional<double> v = parseDouble(n);
    if (!v) {
      if (single) diag.error(n.loc, expected(what, type, n));
      else diag.error(n.loc, std::string(what) + ": expected a number, found " + n.describe());
      return std::nullopt;
    }
    if (!std::isfinite(*v)) {
      diag.error(n.loc, std::string(what) + ": expected a finite number, found " + n.describe());
      return std::nullopt;
    }
    return v;
  }

  std::optional<float> toFloat(const RawNode& n, double v) {
    if (std::fabs(v) > std::numeric_limits<float>::max()) {
      diag.error(n.loc, std::string(what) + ": " + n.scalar + " is out of range for a 32-bit float");
      return std::nullopt;
    }
    // Parse the text as float directly: going through double could round
    // twice and break the exact save/load round trip.
    const char* begin = n.scalar.data();
    const char* end = begin + n.scalar.size();
    if (begin != end && *begin == '+') ++begin;
    float f = 0;
    auto [ptr, ec] = std::from_chars(begin, end, f, std::chars_format::general);
    if (ec == std::errc{} && ptr == end) return f;
    return static_cast<float>(v);
  }

  std::optional<int64_t> integer(const RawNode& n, ValueType type, bool single, int64_t lo, int64_t hi) {
    std::optional<double> asNumber = parseDouble(n);
    int64_t v = 0;
    bool ok = n.isScalar() && !n.quoted && !n.scalar.empty();
    if (ok) {
      const char* begin = n.scalar.data();
      const char* end = begin + n.scalar.size();
      if (*begin == '+') ++begin;
      auto [ptr, ec] = std::from_chars(begin, end, v);
      if (ec == std::errc::result_out_of_range) {
        diag.error(n.loc, std::string(what) + ": " + n.scalar + " is out of range (" + std::to_string(lo) + " to " +
                              std::to_string(hi) + ")");
        return std::nullopt;
      }
      ok = ec == std::errc{} && ptr == end;
    }
    if (!ok) {
      std::string found = asNumber ? "the number " + n.scalar + " (not a whole number)" : n.describe();
      if (single) diag.error(n.loc, std::string(what) + ": expected " + std::string(valueTypeShape(type)) + ", found " + found);
      else diag.error(n.loc, std::string(what) + ": expected an integer, found " + found);
      return std::nullopt;
    }
    if (v < lo || v > hi) {
      diag.error(n.loc, std::string(what) + ": " + n.scalar + " is out of range (" + std::to_string(lo) + " to " +
                            std::to_string(hi) + ")");
      return std::nullopt;
    }
    return v;
  }

  // A list of exactly `count` items, or nullptr after reporting.
  const RawNode* list(const RawNode& n, ValueType type, size_t count) {
    if (!n.isSequence() || n.items.size() != count) {
      diag.error(n.loc, expected(what, type, n));
      return nullptr;
    }
    return &n;
  }

  template <typename Vec>
  std::optional<Vec> floats(const RawNode& n, ValueType type, size_t count) {
    if (!list(n, type, count)) return std::nullopt;
    Vec out;
    for (size_t i = 0; i < count; ++i) {
      auto d = number(n.items[i], type, false);
      if (!d) return std::nullopt;
      if constexpr (std::is_same_v<typename Vec::Scalar, float>) {
        auto f = toFloat(n.items[i], *d);
        if (!f) return std::nullopt;
        out[static_cast<Eigen::Index>(i)] = *f;
      } else {
        out[static_cast<Eigen::Index>(i)] = *d;
      }
    }
    return out;
  }

  std::optional<std::string> string(const RawNode& n, ValueType type) {
    if (!n.isScalar()) {
      diag.error(n.loc, expected(what, type, n));
      return std::nullopt;
    }
    return n.scalar;
  }

  std::optional<std::vector<std::string>> strings(const RawNode& n, ValueType type) {
    if (!n.isSequence()) {
      diag.error(n.loc, expected(what, type, n));
      return std::nullopt;
    }
    std::vector<std::string> out;
    for (const RawNode& item : n.items) {
      if (!item.isScalar()) {
        diag.error(item.loc, std::string(what) + ": expected a string in the list, found " + item.describe());
        return std::nullopt;
      }
      out.push_back(item.scalar);
    }
    return out;
  }

  // float[] is a flat list; the tuple types a list of [x, y(, z)] items.
  std::optional<Value> floatArray(const RawNode& n, ValueType type) {
    if (!n.isSequence()) {
      diag.error(n.loc, expected(what, type, n));
      return std::nullopt;
    }
    const size_t width = size_t(arrayWidth(type));
    std::vector<float> out;
    out.reserve(n.items.size() * width);
    auto push = [&](const RawNode& item) {
      auto d = number(item, type, false);
      if (!d) return false;
      auto f = toFloat(item, *d);
      if (!f) return false;
      out.push_back(*f);
      return true;
    };
    for (const RawNode& item : n.items) {
      if (width == 1) {
        if (!push(item)) return std::nullopt;
        continue;
      }
      if (!item.isSequence() || item.items.size() != width) {
        diag.error(item.loc, std::string(what) + ": expected a list of " + std::to_string(width) +
                                 " numbers in the list, found " + item.describe());
        return std::nullopt;
      }
      for (const RawNode& c : item.items)
        if (!push(c)) return std::nullopt;
    }
    return Value::makeFloatArray(type, std::move(out));
  }

  std::optional<Value> read(const RawNode& n, ValueType type) {
    switch (type) {
      case ValueType::Bool:
        if (n.isScalar() && !n.quoted) {
          const std::string& s = n.scalar;
          if (s == "true" || s == "True" || s == "TRUE") return Value::makeBool(true);
          if (s == "false" || s == "False" || s == "FALSE") return Value::makeBool(false);
        }
        diag.error(n.loc, expected(what, type, n));
        return std::nullopt;
      case ValueType::Int: {
        auto v = integer(n, type, true, std::numeric_limits<int32_t>::min(), std::numeric_limits<int32_t>::max());
        if (!v) return std::nullopt;
        return Value::makeInt(static_cast<int32_t>(*v));
      }
      case ValueType::UInt: {
        auto v = integer(n, type, true, 0, std::numeric_limits<uint32_t>::max());
        if (!v) return std::nullopt;
        return Value::makeUInt(static_cast<uint32_t>(*v));
      }
      case ValueType::Float: {
        auto d = number(n, type, true);
        if (!d) return std::nullopt;
        auto f = toFloat(n, *d);
        if (!f) return std::nullopt;
        return Value::makeFloat(*f);
      }
      case ValueType::Double: {
        auto d = number(n, type, true);
        if (!d) return std::nullopt;
        return Value::makeDouble(*d);
      }
      case ValueType::Int2: {
        if (!list(n, type, 2)) return std::nullopt;
        constexpr int64_t lo = std::numeric_limits<int32_t>::min(), hi = std::numeric_limits<int32_t>::max();
        auto x = integer(n.items[0], type, false, lo, hi);
        if (!x) return std::nullopt;
        auto y = integer(n.items[1], type, false, lo, hi);
        if (!y) return std::nullopt;
        return Value::makeInt2(static_cast<int32_t>(*x), static_cast<int32_t>(*y));
      }
      case ValueType::Float2: {
        auto v = floats<Vec2f>(n, type, 2);
        if (!v) return std::nullopt;
        return Value::makeFloat2(v->x(), v->y());
      }
      case ValueType::Float3:
      case ValueType::Color3f: {
        auto v = floats<Vec3f>(n, type, 3);
        if (!v) return std::nullopt;
        return type == ValueType::Float3 ? Value::makeFloat3(*v) : Value::makeColor3f(*v);
      }
      case ValueType::Double3:
      case ValueType::Vector3d: {
        auto v = floats<Vec3d>(n, type, 3);
        if (!v) return std::nullopt;
        return type == ValueType::Double3 ? Value::makeDouble3(*v) : Value::makeVector3d(*v);
      }
      case ValueType::Quatf: {
        auto v = floats<Eigen::Vector4f>(n, type, 4);
        if (!v) return std::nullopt;
        return Value::makeQuatf(Quatf((*v)[0], (*v)[1], (*v)[2], (*v)[3]));
      }
      case ValueType::Quatd: {
        auto v = floats<Eigen::Vector4d>(n, type, 4);
        if (!v) return std::nullopt;
        return Value::makeQuatd(Quatd((*v)[0], (*v)[1], (*v)[2], (*v)[3]));
      }
      case ValueType::Matrix4d: {
        if (!list(n, type, 4)) return std::nullopt;
        Matrix4d m;
        for (int row = 0; row < 4; ++row) {
          auto r = floats<Eigen::Vector4d>(n.items[static_cast<size_t>(row)], type, 4);
          if (!r) return std::nullopt;
          // USD rows (row-vector convention) are our columns.
          m.col(row) = *r;
        }
        return Value::makeMatrix4d(m);
      }
      case ValueType::String:
      case ValueType::Token:
      case ValueType::Asset: {
        auto s = string(n, type);
        if (!s) return std::nullopt;
        if (type == ValueType::String) return Value::makeString(*s);
        if (type == ValueType::Token) return Value::makeToken(*s);
        return Value::makeAsset(*s);
      }
      case ValueType::AssetArray:
      case ValueType::StringArray: {
        auto v = strings(n, type);
        if (!v) return std::nullopt;
        return type == ValueType::AssetArray ? Value::makeAssetArray(*v) : Value::makeStringArray(*v);
      }
      case ValueType::IntArray: {
        if (!n.isSequence()) {
          diag.error(n.loc, expected(what, type, n));
          return std::nullopt;
        }
        std::vector<int32_t> out;
        out.reserve(n.items.size());
        for (const RawNode& item : n.items) {
          auto v = integer(item, type, false, std::numeric_limits<int32_t>::min(), std::numeric_limits<int32_t>::max());
          if (!v) return std::nullopt;
          out.push_back(static_cast<int32_t>(*v));
        }
        return Value::makeIntArray(std::move(out));
      }
      case ValueType::FloatArray:
      case ValueType::Point3fArray:
      case ValueType::Normal3fArray:
      case ValueType::Color3fArray:
      case ValueType::TexCoord2fArray: return floatArray(n, type);
    }
    return std::nullopt;
  }
};

// Smallest component of a numeric value, for `minimum` checks.
std::optional<double> smallestComponent(const Value& v) {
  switch (v.type()) {
    case ValueType::Int: return v.get<int32_t>();
    case ValueType::UInt: return v.get<uint32_t>();
    case ValueType::Float: return v.get<float>();
    case ValueType::Double: return v.get<double>();
    case ValueType::Int2: return v.get<Vec2i>().minCoeff();
    case ValueType::Float2: return v.get<Vec2f>().minCoeff();
    case ValueType::Float3:
    case ValueType::Color3f: return v.get<Vec3f>().minCoeff();
    case ValueType::Double3:
    case ValueType::Vector3d: return v.get<Vec3d>().minCoeff();
    default: return std::nullopt;
  }
}

}  // namespace

std::optional<Value> readValue(const RawNode& node, ValueType type, std::string_view what, Diagnostics& diag) {
  return Reader{what, diag}.read(node, type);
}

std::optional<Value> readValue(const RawNode& node, const AttributeSpec& spec, std::string_view what,
                               Diagnostics& diag) {
  std::optional<Value> v = readValue(node, spec.type, what, diag);
  if (!v) return v;
  if (spec.minimum) {
    std::optional<double> smallest = smallestComponent(*v);
    if (smallest && *smallest < *spec.minimum) {
      diag.error(node.loc, std::string(what) + ": must be at least " + text::formatNumber(*spec.minimum) +
                               (v->type() == ValueType::Double || v->type() == ValueType::Float ||
                                        v->type() == ValueType::Int || v->type() == ValueType::UInt
                                    ? ""
                                    : " in every component") +
                               ", found " + v->toString());
      return std::nullopt;
    }
  }
  if (!spec.allowedTokens.empty()) {
    const std::string& token = v->get<std::string>();
    bool allowed = false;
    for (const std::string& t : spec.allowedTokens) allowed = allowed || t == token;
    if (!allowed) {
      diag.error(node.loc, std::string(what) + ": expected one of " + text::join(spec.allowedTokens, ", ") +
                               ", found " + text::quote(token) + text::didYouMean(token, spec.allowedTokens));
      return std::nullopt;
    }
  }
  return v;
}

std::optional<std::string> readString(const RawNode& node, std::string_view what, Diagnostics& diag) {
  std::optional<Value> v = readValue(node, ValueType::String, what, diag);
  if (!v) return std::nullopt;
  return v->get<std::string>();
}

std::optional<double> readNumber(const RawNode& node, std::string_view what, Diagnostics& diag) {
  std::optional<Value> v = readValue(node, ValueType::Double, what, diag);
  if (!v) return std::nullopt;
  return v->get<double>();
}

}  // namespace sdg
