// The .usda parser: metadata entries of layers, prims, variants and
// properties. The composition arcs and Sdf's well-known keys get their Sdf
// types; any other key is kept under its name with a type read off its
// value (numbers as double, quoted text as string, lists as vectors).
#include <unordered_map>

#include "usd/sdf_path.h"
#include "usd/usda_parser.h"

namespace sdg::usd {

namespace {

enum class MetaType { Token, String, Double, Int, Bool, Dictionary, TokenVector, Asset, TokenListOp, StringListOp };

const std::unordered_map<std::string_view, MetaType>& knownMetadata() {
  static const std::unordered_map<std::string_view, MetaType> kTable = {
      {"kind", MetaType::Token},
      {"defaultPrim", MetaType::Token},
      {"upAxis", MetaType::Token},
      {"interpolation", MetaType::Token},
      {"colorSpace", MetaType::Token},
      {"connectability", MetaType::Token},
      {"renderType", MetaType::Token},
      {"bindMaterialAs", MetaType::Token},
      {"outputName", MetaType::Token},
      {"colorManagementSystem", MetaType::Token},
      {"documentation", MetaType::String},
      {"comment", MetaType::String},
      {"displayName", MetaType::String},
      {"displayGroup", MetaType::String},
      {"owner", MetaType::String},
      {"sessionOwner", MetaType::String},
      {"renderSettingsPrimPath", MetaType::String},
      {"metersPerUnit", MetaType::Double},
      {"kilogramsPerUnit", MetaType::Double},
      {"startTimeCode", MetaType::Double},
      {"endTimeCode", MetaType::Double},
      {"timeCodesPerSecond", MetaType::Double},
      {"framesPerSecond", MetaType::Double},
      {"startFrame", MetaType::Double},
      {"endFrame", MetaType::Double},
      {"elementSize", MetaType::Int},
      {"framePrecision", MetaType::Int},
      {"unauthoredValuesIndex", MetaType::Int},
      {"active", MetaType::Bool},
      {"hidden", MetaType::Bool},
      {"instanceable", MetaType::Bool},
      {"customData", MetaType::Dictionary},
      {"assetInfo", MetaType::Dictionary},
      {"customLayerData", MetaType::Dictionary},
      {"clips", MetaType::Dictionary},
      {"sdrMetadata", MetaType::Dictionary},
      {"expressionVariables", MetaType::Dictionary},
      {"allowedTokens", MetaType::TokenVector},
      {"colorConfiguration", MetaType::Asset},
      {"apiSchemas", MetaType::TokenListOp},
      {"clipSets", MetaType::StringListOp},
  };
  return kTable;
}

Value textListOpValue(Kind kind) {
  Value v;
  v.kind = kind;
  v.textListOp = std::make_shared<ListOp<std::string>>();
  return v;
}

// The existing list-op field `key` of `spec`, or a new one of `kind`.
Value& listOpField(Spec& spec, const std::string& key, Kind kind) {
  Value& v = spec.fields[key];
  if (v.kind != kind) {
    if (kind == Kind::ReferenceListOp || kind == Kind::PayloadListOp) {
      v = Value{};
      v.kind = kind;
      v.referenceListOp = std::make_shared<ListOp<Reference>>();
    } else if (kind == Kind::Int64ListOp) {
      v = Value{};
      v.kind = kind;
      v.intListOp = std::make_shared<ListOp<int64_t>>();
    } else {
      v = textListOpValue(kind);
    }
  }
  return v;
}

const char* describeOwner(int owner) {
  return owner == 0 ? "the layer" : owner == 1 ? "a prim" : owner == 2 ? "an attribute" : "a relationship";
}

}  // namespace

void UsdaParser::parseMetadataEntry(Spec& spec, Owner owner) {
  if (tok_.kind == TokenKind::String) {  // a bare string: the comment
    spec.fields[field::kComment] = Value::text(Kind::String, decodeString(tok_));
    advance();
    return;
  }
  std::string listOp;
  if (isListOpWord() && peek().kind == TokenKind::Identifier) {
    listOp = std::string(tok_.text);
    advance();
  }
  Token keyToken = tok_;
  std::string key = expectIdentifier("a metadata key, a quoted comment or ')'");
  expectPunct('=', ("after '" + key + "'").c_str());
  auto onlyOn = [&](Owner allowed) {
    if (owner != allowed)
      fail(keyToken, "'" + key + "' is metadata of " + describeOwner(static_cast<int>(allowed)) +
                         "; it cannot appear on " + describeOwner(static_cast<int>(owner)));
  };
  auto noListOp = [&] {
    if (!listOp.empty()) fail(keyToken, "'" + key + "' is not a list: '" + listOp + "' does not apply to it");
  };

  if (key == "references" || key == "payload") {
    onlyOn(Owner::Prim);
    bool payload = key == "payload";
    Value& v = listOpField(spec, key, payload ? Kind::PayloadListOp : Kind::ReferenceListOp);
    setListOpItems(*v.referenceListOp, listOp, parseReferenceList(payload));
  } else if (key == "inherits" || key == "specializes") {
    onlyOn(Owner::Prim);
    Value& v = listOpField(spec, key == "inherits" ? field::kInheritPaths : field::kSpecializes, Kind::PathListOp);
    setListOpItems(*v.textListOp, listOp, parsePathList(true, true));
  } else if (key == "variantSets") {
    onlyOn(Owner::Prim);
    Value& v = listOpField(spec, field::kVariantSetNames, Kind::StringListOp);
    std::vector<std::string> names = tok_.isWord("None") ? (advance(), std::vector<std::string>{}) : parseNameList();
    setListOpItems(*v.textListOp, listOp, std::move(names));
  } else if (key == "variants") {
    onlyOn(Owner::Prim);
    noListOp();
    Token at = tok_;
    Value v = parseTypedDictionary();
    for (const auto& [set, selection] : *v.dictionary)
      if (selection.kind != Kind::String || selection.isArray)
        fail(at, "variant selections must be strings: '" + set + "' is a " + kindName(selection.kind));
    v.kind = Kind::VariantSelectionMap;
    spec.fields[field::kVariantSelection] = std::move(v);
  } else if (key == "subLayers") {
    onlyOn(Owner::Layer);
    noListOp();
    parseSubLayers(spec);
  } else if (key == "relocates") {
    noListOp();
    spec.fields[field::kRelocates] = parseRelocates();
  } else if (key == "prefixSubstitutions" || key == "suffixSubstitutions") {
    noListOp();
    spec.fields[key] = parseStringDictionary();
  } else if (key == "permission") {
    noListOp();
    Token at = tok_;
    std::string value = expectIdentifier("'public' or 'private'");
    if (value != "public" && value != "private") fail(at, "expected 'public' or 'private', found '" + value + "'");
    Value v;
    v.kind = Kind::Permission;
    v.enumValue = static_cast<int>(value == "public" ? Permission::Public : Permission::Private);
    spec.fields[field::kPermission] = v;
  } else if (key == "symmetryFunction" || key == "displayUnit") {
    noListOp();
    std::string value;
    if (tok_.kind == TokenKind::Identifier && !tok_.newlineBefore) value = expectIdentifier("a name");
    spec.fields[key] = Value::text(Kind::Token, value);
  } else if (key == "doc") {
    noListOp();
    spec.fields[field::kDocumentation] = Value::text(Kind::String, expectString("a quoted documentation string"));
  } else if (!listOp.empty()) {
    // A list op of any other key: apiSchemas (tokens), clipSets (strings), or
    // a key this reader does not know, typed by its items.
    auto known = knownMetadata().find(key);
    if (known != knownMetadata().end() && known->second != MetaType::TokenListOp &&
        known->second != MetaType::StringListOp)
      fail(keyToken, "'" + key + "' is not a list: '" + listOp + "' does not apply to it");
    if (tok_.is('[') && peek().kind == TokenKind::Number) {
      Value& v = listOpField(spec, key, Kind::Int64ListOp);
      std::vector<int64_t> items;
      advance();
      while (!tok_.is(']')) {
        items.push_back(static_cast<int64_t>(parseNumber(Kind::Int64)));
        if (tok_.is(',')) advance();
        else if (!tok_.is(']')) expected("',' or ']' in the list");
      }
      advance();
      setListOpItems(*v.intListOp, listOp, std::move(items));
    } else if (tok_.kind == TokenKind::Path || (tok_.is('[') && peek().kind == TokenKind::Path)) {
      Value& v = listOpField(spec, key, Kind::PathListOp);
      setListOpItems(*v.textListOp, listOp, parsePathList(true, false));
    } else {
      bool strings = known != knownMetadata().end() && known->second == MetaType::StringListOp;
      Value& v = listOpField(spec, key, strings ? Kind::StringListOp : Kind::TokenListOp);
      std::vector<std::string> names = tok_.isWord("None") ? (advance(), std::vector<std::string>{}) : parseNameList();
      setListOpItems(*v.textListOp, listOp, std::move(names));
    }
  } else {
    spec.fields[key] = parseMetadataValue(key, keyToken);
  }
}

Value UsdaParser::parseMetadataValue(const std::string& key, const Token& keyToken) {
  if (tok_.isWord("None")) {  // an authored "no value"
    advance();
    return Value::block();
  }
  auto known = knownMetadata().find(key);
  if (known == knownMetadata().end()) {
    if (tok_.is('{')) return parseTypedDictionary();
    return parseGenericValue();
  }
  switch (known->second) {
    case MetaType::Token: return Value::text(Kind::Token, expectString(("a quoted token for '" + key + "'").c_str()));
    case MetaType::String: return Value::text(Kind::String, expectString(("a quoted string for '" + key + "'").c_str()));
    case MetaType::Double: return parseTypedValue({Kind::Double, false}, "double");
    case MetaType::Int: return parseTypedValue({Kind::Int, false}, "int");
    case MetaType::Bool: return parseTypedValue({Kind::Bool, false}, "bool");
    case MetaType::Dictionary: return parseTypedDictionary();
    case MetaType::Asset: return parseTypedValue({Kind::AssetPath, false}, "asset");
    case MetaType::TokenVector: {
      std::vector<std::string> names = parseNameList();
      return Value::textArray(Kind::TokenVector, std::move(names));
    }
    case MetaType::TokenListOp:
    case MetaType::StringListOp: {  // written without a prefix: the explicit list
      Value v = textListOpValue(known->second == MetaType::TokenListOp ? Kind::TokenListOp : Kind::StringListOp);
      setListOpItems(*v.textListOp, "", parseNameList());
      return v;
    }
  }
  fail(keyToken, "unhandled metadata '" + key + "'");
}

// A value with no declared type: its kind follows from what is written.
Value UsdaParser::parseGenericValue() {
  switch (tok_.kind) {
    case TokenKind::Number: return parseTypedValue({Kind::Double, false}, "double");
    case TokenKind::String: return parseTypedValue({Kind::String, false}, "string");
    case TokenKind::Asset: return parseTypedValue({Kind::AssetPath, false}, "asset");
    case TokenKind::Path: {
      std::string p(tok_.text);
      advance();
      return Value::textArray(Kind::PathVector, {p});
    }
    case TokenKind::Identifier: {
      if (tok_.isWord("true") || tok_.isWord("false")) return parseTypedValue({Kind::Bool, false}, "bool");
      if (tok_.isWord("inf") || tok_.isWord("nan")) return parseTypedValue({Kind::Double, false}, "double");
      Value v = Value::text(Kind::Token, std::string(tok_.text));
      advance();
      return v;
    }
    default: break;
  }
  if (tok_.is('(')) {  // a tuple of numbers: a double vector of its size
    Token open = tok_;
    NestingGuard guard(*this, "tuples");
    advance();
    std::vector<double> numbers;
    while (!tok_.is(')')) {
      if (numbers.size() >= 16) fail(open, "an untyped tuple of more than 16 numbers");
      numbers.push_back(parseNumber(Kind::Double));
      if (tok_.is(',')) advance();
      else if (!tok_.is(')')) expected("',' or ')' in the tuple");
    }
    advance();
    static const Kind kBySize[] = {Kind::Empty, Kind::Double, Kind::Vec2d, Kind::Vec3d, Kind::Vec4d};
    if (numbers.size() >= 2 && numbers.size() <= 4) return Value::scalar(kBySize[numbers.size()], numbers);
    if (numbers.size() == 16) return Value::scalar(Kind::Matrix4d, numbers);
    fail(open, "an untyped tuple of " + std::to_string(numbers.size()) + " numbers: declare the metadata's type");
  }
  if (tok_.is('[')) {  // a list: typed by its first item
    const Token& first = peek();
    if (first.is(']')) {
      advance();
      advance();
      return Value::textArray(Kind::StringVector, {});
    }
    if (first.kind == TokenKind::String) return parseTypedValue({Kind::String, true}, "string[]");
    if (first.kind == TokenKind::Asset) return parseTypedValue({Kind::AssetPath, true}, "asset[]");
    if (first.kind == TokenKind::Number) return parseTypedValue({Kind::Double, true}, "double[]");
    if (first.kind == TokenKind::Path) return Value::textArray(Kind::PathVector, parsePathList(false, false));
    if (first.isWord("true") || first.isWord("false")) return parseTypedValue({Kind::Bool, true}, "bool[]");
    advance();
    expected("strings, numbers, asset paths or paths in the untyped list");
  }
  expected("a value");
}

}  // namespace sdg::usd
