// The .usda parser: typed values (scalars, tuples, matrices, arrays), time
// samples, typed dictionaries, paths, name lists, references and payloads,
// sublayer lists. Attribute values are parsed straight into Value's flat
// number store: the type is known before the value, so no intermediate
// tree is built for the large arrays that dominate real files.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "core/text.h"
#include "usd/sdf_path.h"
#include "usd/usda_parser.h"

namespace sdg::usd {

namespace {

// The nearest IEEE half value (round half to even), as crate files would hold it.
double roundToHalf(double v) {
  if (!std::isfinite(v)) return v;
  double a = std::fabs(v);
  if (a >= 65520.0) return std::copysign(std::numeric_limits<double>::infinity(), v);
  int e = 0;
  std::frexp(a, &e);
  int exponent = std::max(e - 1, -14);  // subnormal halves share the smallest exponent
  double quantum = std::ldexp(1.0, exponent - 10);
  return std::copysign(std::nearbyint(a / quantum) * quantum, v);
}

struct IntRange {
  double min, max;
};
std::optional<IntRange> integerRange(Kind kind) {
  switch (kind) {
    case Kind::UChar: return IntRange{0, 255};
    case Kind::Int: return IntRange{-2147483648.0, 2147483647.0};
    case Kind::UInt: return IntRange{0, 4294967295.0};
    case Kind::Int64: return IntRange{-9223372036854775808.0, 9223372036854775807.0};
    case Kind::UInt64: return IntRange{0, 18446744073709551615.0};
    default: return std::nullopt;
  }
}

// A number read for a component of `kind`: integers must be whole and in
// range; float and half values take their type's precision. False when the
// number does not fit (the caller reports it).
bool fitNumber(Kind kind, double& value) {
  if (kind == Kind::Bool) {
    value = value != 0 ? 1 : 0;
  } else if (auto range = integerRange(kind)) {
    return value == std::floor(value) && value >= range->min && value <= range->max;
  } else if (kind == Kind::Float) {
    value = static_cast<double>(static_cast<float>(value));
  } else if (kind == Kind::Half) {
    value = roundToHalf(value);
  }
  return true;
}

}  // namespace

double UsdaParser::parseNumber(Kind kind) {
  double value = 0;
  if (tok_.kind == TokenKind::Number) {
    std::string_view t = tok_.text;
    if (t == "-inf") {
      value = -std::numeric_limits<double>::infinity();
    } else {
      auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
      if (ec == std::errc::result_out_of_range) {
        bool tiny = t.find_first_of("eE") != std::string_view::npos && t.find("e-") != std::string_view::npos;
        value = tiny ? 0.0 : std::numeric_limits<double>::infinity();
        if (t[0] == '-') value = -value;
      } else if (ec != std::errc() || end != t.data() + t.size()) {
        expected("a number");
      }
    }
  } else if (tok_.isWord("inf")) {
    value = std::numeric_limits<double>::infinity();
  } else if (tok_.isWord("nan")) {
    value = std::numeric_limits<double>::quiet_NaN();
  } else if (kind == Kind::Bool && (tok_.isWord("true") || tok_.isWord("false"))) {
    value = tok_.isWord("true") ? 1 : 0;
  } else {
    expected(std::string("a ") + (kind == Kind::Bool ? "bool (true, false, 1 or 0)" : std::string(kindName(kind)) + " number"));
  }
  if (!fitNumber(kind, value))
    fail(tok_, "expected an " + std::string(kindName(kind)) + ", found " + describe(tok_) +
                   (value != std::floor(value) ? "" : " (out of range)"));
  advance();
  return value;
}

// The fast path for the large numeric arrays that make up most of a real
// file (points, normals, UVs, indices): numbers and tuples read straight
// from the text with from_chars, no tokens made. It stops at the first
// thing it does not handle — a comment, inf or nan, a number that does not
// fit, anything malformed — leaving the text from the start of that element
// to the token path, which reads it or reports the error at its exact
// place. Returns true when it read the array through its closing ']'.
bool UsdaParser::scanNumberArray(Kind kind, std::vector<double>& numbers, uint64_t& count) {
  if (hasPeek_ || kind == Kind::Bool || !isNumeric(kind) || matrixDimension(kind)) return false;
  const int components = componentCount(kind);
  const Kind scalar = componentKind(kind);
  const std::string_view text = lexer_.text();
  const size_t size = text.size();
  UsdaLexer::State at = UsdaLexer::stateAt(tok_);
  size_t pos = at.pos;
  auto skipSpace = [&] {  // false at a comment
    while (pos < size) {
      char c = text[pos];
      if (c == ' ' || c == '\t') {
        ++pos;
      } else if (c == '\n' || c == '\r') {
        ++pos;
        if (c == '\r' && pos < size && text[pos] == '\n') ++pos;
        ++at.line;
        at.lineStart = pos;
      } else {
        return c != '#' && c != '/';
      }
    }
    return true;
  };
  auto number = [&](double& out) {
    size_t digits = pos < size && text[pos] == '-' ? pos + 1 : pos;
    if (digits >= size || !((text[digits] >= '0' && text[digits] <= '9') || text[digits] == '.')) return false;
    auto [end, ec] = std::from_chars(text.data() + pos, text.data() + size, out);
    if (ec != std::errc()) return false;
    size_t after = static_cast<size_t>(end - text.data());
    if (after < size) {
      char d = text[after];
      if (d != ',' && d != ')' && d != ']' && d != ' ' && d != '\t' && d != '\n' && d != '\r') return false;
    }
    pos = after;
    return fitNumber(scalar, out);
  };
  auto element = [&] {
    double x = 0;
    if (components == 1) {
      if (!number(x)) return false;
      numbers.push_back(x);
      return true;
    }
    if (pos >= size || text[pos] != '(') return false;
    ++pos;
    for (int i = 0; i < components; ++i) {
      if (i > 0) {
        if (!skipSpace() || pos >= size || text[pos] != ',') return false;
        ++pos;
      }
      if (!skipSpace() || !number(x)) return false;
      numbers.push_back(x);
    }
    if (!skipSpace()) return false;
    if (pos < size && text[pos] == ',' && (++pos, !skipSpace())) return false;
    if (pos >= size || text[pos] != ')') return false;
    ++pos;
    return true;
  };
  while (true) {
    UsdaLexer::State start = at;
    start.pos = pos;
    size_t mark = numbers.size();
    auto handOver = [&] {  // back to the start of this element, for the token path
      numbers.resize(mark);
      lexer_.restore(start);
      advance();
      return false;
    };
    if (!skipSpace()) return handOver();
    if (pos < size && text[pos] == ']') {
      at.pos = pos + 1;
      lexer_.restore(at);
      advance();
      return true;
    }
    if (count >= limits_.maxArrayElements || !element() || !skipSpace()) return handOver();
    if (pos < size && text[pos] == ',') {
      ++pos;
    } else if (pos >= size || text[pos] != ']') {
      return handOver();
    }
    ++count;
  }
}

void UsdaParser::parseElement(Kind kind, std::vector<double>& numbers, std::vector<std::string>& strings) {
  if (isText(kind)) {
    bool asset = kind == Kind::AssetPath;
    if (tok_.kind != (asset ? TokenKind::Asset : TokenKind::String))
      expected(asset ? "an asset path (@path@)" : std::string("a quoted ") + kindName(kind));
    strings.push_back(decodeString(tok_));
    advance();
    return;
  }
  int components = componentCount(kind);
  if (components == 1) {
    numbers.push_back(parseNumber(kind));
    return;
  }
  Kind scalar = componentKind(kind);
  int rows = matrixDimension(kind);
  int perTuple = rows ? rows : components;
  auto tuple = [&](const char* what) {
    if (!tok_.is('(')) expected(std::string("'(' to start ") + what);
    advance();
    for (int i = 0; i < perTuple; ++i) {
      if (i > 0) {
        if (!tok_.is(',')) expected("',' and " + std::to_string(perTuple - i) + " more numbers in " + what);
        advance();
      }
      numbers.push_back(parseNumber(scalar));
    }
    if (tok_.is(',')) advance();
    if (!tok_.is(')')) expected(std::string("')' after ") + std::to_string(perTuple) + " numbers in " + what);
    advance();
  };
  std::string what = std::string("a ") + kindName(kind) + (rows ? " row" : " value");
  if (!rows) {
    tuple(what.c_str());
    return;
  }
  if (!tok_.is('(')) expected(std::string("'(' to start a ") + kindName(kind));
  advance();
  for (int r = 0; r < rows; ++r) {
    if (r > 0) {
      if (!tok_.is(',')) expected("',' and the next row of the " + std::string(kindName(kind)));
      advance();
    }
    tuple(what.c_str());
  }
  if (tok_.is(',')) advance();
  if (!tok_.is(')')) expected(std::string("')' after the ") + std::to_string(rows) + " rows of the " + kindName(kind));
  advance();
}

Value UsdaParser::parseTypedValue(ValueType type, const std::string& typeName) {
  Value v;
  v.kind = type.kind;
  v.isArray = type.isArray;
  if (!type.isArray) {
    parseElement(type.kind, v.numbers, v.strings);
    return v;
  }
  NestingGuard guard(*this, "arrays");
  if (!tok_.is('[')) expected("'[' to start the " + typeName + " value");
  advance();
  uint64_t count = 0;
  if (scanNumberArray(type.kind, v.numbers, count)) return v;
  while (!tok_.is(']')) {
    if (++count > limits_.maxArrayElements)
      fail(tok_, "the " + typeName + " array has more than " + std::to_string(limits_.maxArrayElements) +
                     " elements, the limit");
    parseElement(type.kind, v.numbers, v.strings);
    if (tok_.is(',')) {
      advance();
    } else if (!tok_.is(']')) {
      expected("',' or ']' in the " + typeName + " array");
    }
  }
  advance();
  return v;
}

Value UsdaParser::parseTimeSamples(ValueType type, const std::string& typeName) {
  NestingGuard guard(*this, "time samples");
  expectPunct('{', "to start the time samples");
  std::vector<std::pair<double, Value>> samples;
  while (!tok_.is('}')) {
    if (samples.size() >= limits_.maxArrayElements) fail(tok_, "too many time samples");
    double time = parseNumber(Kind::Double);
    if (!std::isfinite(time)) fail(tok_, "a time sample's time must be a finite number");
    expectPunct(':', "after the sample's time");
    if (tok_.isWord("None")) {
      advance();
      samples.emplace_back(time, Value::block());
    } else {
      samples.emplace_back(time, parseTypedValue(type, typeName));
    }
    if (tok_.is(',')) {
      advance();
    } else if (!tok_.is('}')) {
      expected("',' or '}' after the time sample");
    }
  }
  advance();
  // Times in order; a time written twice keeps its last value, as Sdf does.
  std::stable_sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  auto ts = std::make_shared<TimeSamples>();
  for (auto& [time, value] : samples) {
    if (!ts->times.empty() && ts->times.back() == time) {
      ts->values.back() = std::move(value);
      continue;
    }
    ts->times.push_back(time);
    ts->values.push_back(std::move(value));
  }
  Value v;
  v.kind = Kind::TimeSamples;
  v.timeSamples = std::move(ts);
  return v;
}

Value UsdaParser::parseTypedDictionary() {
  NestingGuard guard(*this, "dictionaries");
  expectPunct('{', "to start the dictionary");
  Dictionary dict;
  while (!tok_.is('}')) {
    Token typeToken = tok_;
    std::string typeName = expectIdentifier("a value type and a key, or '}'");
    bool nested = typeName == "dictionary";
    if (!nested && tok_.is('[')) {
      advance();
      expectPunct(']', "to close the array type");
      typeName += "[]";
    }
    if (tok_.kind != TokenKind::String && tok_.kind != TokenKind::Identifier) expected("the dictionary key");
    std::string key = decodeString(tok_);
    advance();
    expectPunct('=', "after the dictionary key");
    if (nested) {
      dict[key] = parseTypedDictionary();
    } else {
      std::optional<ValueType> type = valueTypeForName(typeName);
      if (!type) {
        std::string base = typeName.substr(0, typeName.find('['));
        fail(typeToken, "unknown value type '" + base + "'" + text::didYouMean(base, valueTypeNames()));
      }
      dict[key] = parseTypedValue(*type, typeName);
    }
    endStatement('}', "the dictionary entry");
  }
  advance();
  return Value::dict(std::move(dict));
}

std::string UsdaParser::parsePath(bool primPathOnly) {
  if (tok_.kind != TokenKind::Path) expected(primPathOnly ? "a prim path (<...>)" : "a path (<...>)");
  std::string written(tok_.text);
  if (written.empty()) fail(tok_, "empty path <>");
  if (!path::isValidPath(written)) fail(tok_, describe(tok_) + " is not a valid path");
  std::string absolute = path::makeAbsolute(anchor_, written);
  if (absolute.empty()) fail(tok_, "the path <" + written + "> climbs above the root");
  if (primPathOnly && absolute.size() != path::primPart(absolute).size())
    fail(tok_, "expected a prim path, found the property path <" + written + ">");
  advance();
  return absolute;
}

std::vector<std::string> UsdaParser::parsePathList(bool allowNone, bool primPathsOnly) {
  std::vector<std::string> paths;
  if (allowNone && tok_.isWord("None")) {
    advance();
    return paths;
  }
  if (!tok_.is('[')) {
    paths.push_back(parsePath(primPathsOnly));
    return paths;
  }
  advance();
  while (!tok_.is(']')) {
    if (paths.size() >= limits_.maxArrayElements) fail(tok_, "too many paths in the list");
    paths.push_back(parsePath(primPathsOnly));
    if (tok_.is(',')) advance();
    else if (!tok_.is(']')) expected("',' or ']' in the path list");
  }
  advance();
  return paths;
}

std::vector<std::string> UsdaParser::parseNameList() {
  std::vector<std::string> names;
  if (tok_.kind == TokenKind::String) {
    names.push_back(decodeString(tok_));
    advance();
    return names;
  }
  expectPunct('[', "or a quoted name to start the name list");
  while (!tok_.is(']')) {
    if (names.size() >= limits_.maxArrayElements) fail(tok_, "too many names in the list");
    names.push_back(expectString("a quoted name"));
    if (tok_.is(',')) advance();
    else if (!tok_.is(']')) expected("',' or ']' in the name list");
  }
  advance();
  return names;
}

// `(offset = 10; scale = 2)` after a sublayer, and also `customData = {...}`
// after a reference (`reference` non-null).
LayerOffset UsdaParser::parseLayerOffsetEntries(Reference* reference) {
  LayerOffset offset;
  advance();  // '('
  while (!tok_.is(')')) {
    Token key = tok_;
    if (tok_.isWord("offset") || tok_.isWord("scale")) {
      advance();
      expectPunct('=', "after the layer offset's key");
      double value = parseNumber(Kind::Double);
      if (!std::isfinite(value)) fail(key, "a layer " + std::string(key.text) + " must be a finite number");
      (key.isWord("offset") ? offset.offset : offset.scale) = value;
    } else if (reference && tok_.isWord("customData")) {
      advance();
      expectPunct('=', "after 'customData'");
      reference->customData = parseTypedDictionary().dictionary;
    } else {
      expected(reference ? "'offset', 'scale' or 'customData'" : "'offset' or 'scale'");
    }
    endStatement(')', "the layer offset entry");
  }
  advance();
  return offset;
}

std::vector<Reference> UsdaParser::parseReferenceList(bool payload) {
  std::vector<Reference> refs;
  if (tok_.isWord("None")) {
    advance();
    return refs;
  }
  auto item = [&] {
    Reference ref;
    const char* arc = payload ? "payload" : "reference";
    ref.loc = here();
    if (tok_.kind == TokenKind::Asset) {
      if (tok_.text.empty())
        fail(tok_, std::string("a ") + arc + "'s asset path must not be empty (write only the <path> for an internal " +
                       arc + ")");
      ref.assetPath = decodeString(tok_);
      advance();
      if (tok_.kind == TokenKind::Path) ref.primPath = parsePath(true);
    } else if (tok_.kind == TokenKind::Path) {
      ref.primPath = parsePath(true);
    } else {
      expected(std::string("an asset path (@file@) or a prim path (<path>) for the ") + arc);
    }
    if (tok_.is('(')) ref.offset = parseLayerOffsetEntries(&ref);
    refs.push_back(std::move(ref));
  };
  if (!tok_.is('[')) {
    item();
    return refs;
  }
  NestingGuard guard(*this, "lists");
  advance();
  while (!tok_.is(']')) {
    if (refs.size() >= limits_.maxArrayElements) fail(tok_, "too many references in the list");
    item();
    if (tok_.is(',')) advance();
    else if (!tok_.is(']')) expected("',' or ']' in the list");
  }
  advance();
  return refs;
}

void UsdaParser::parseSubLayers(Spec& pseudoRoot) {
  expectPunct('[', "to start the sublayer list");
  std::vector<std::string> layers;
  auto offsets = std::make_shared<std::vector<LayerOffset>>();
  while (!tok_.is(']')) {
    if (layers.size() >= limits_.maxArrayElements) fail(tok_, "too many sublayers");
    if (tok_.kind != TokenKind::Asset) expected("a sublayer's asset path (@file@)");
    if (tok_.text.empty()) fail(tok_, "a sublayer's asset path must not be empty");
    layers.push_back(decodeString(tok_));
    layer_.subLayerLocs.push_back(here());
    advance();
    offsets->push_back(tok_.is('(') ? parseLayerOffsetEntries(nullptr) : LayerOffset{});
    if (tok_.is(',')) advance();
    else if (!tok_.is(']')) expected("',' or ']' in the sublayer list");
  }
  advance();
  pseudoRoot.fields[field::kSubLayers] = Value::textArray(Kind::StringVector, std::move(layers));
  Value v;
  v.kind = Kind::LayerOffsetVector;
  v.layerOffsets = std::move(offsets);
  pseudoRoot.fields[field::kSubLayerOffsets] = std::move(v);
}

Value UsdaParser::parseStringDictionary() {
  expectPunct('{', "to start the string dictionary");
  Dictionary dict;
  while (!tok_.is('}')) {
    std::string key = expectString("a quoted key");
    expectPunct(':', "after the key");
    dict[key] = Value::text(Kind::String, expectString("a quoted value"));
    if (tok_.is(',')) advance();
    else if (!tok_.is('}')) expected("',' or '}' in the dictionary");
  }
  advance();
  return Value::dict(std::move(dict));
}

Value UsdaParser::parseRelocates() {
  expectPunct('{', "to start the relocates");
  Dictionary dict;
  while (!tok_.is('}')) {
    std::string source = parsePath(true);
    expectPunct(':', "after the relocated path");
    dict[source] = Value::text(Kind::String, parsePath(true));
    if (tok_.is(',')) advance();
    else if (!tok_.is('}')) expected("',' or '}' in the relocates");
  }
  advance();
  return Value::dict(std::move(dict));
}

}  // namespace sdg::usd
