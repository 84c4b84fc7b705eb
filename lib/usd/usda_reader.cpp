// The .usda parser: the layer's structure (metadata blocks, prims,
// properties, variant sets). Values are parsed in usda_values.cpp.
#include <algorithm>

#include "core/text.h"
#include "usd/layer_io.h"
#include "usd/sdf_path.h"
#include "usd/usda_parser.h"

namespace sdg::usd {

namespace {

// The first line: "#usda 1.0". Returns the offset just past it.
size_t checkHeader(std::string_view text, const FileName& file) {
  std::string_view cookie = "#usda ";
  if (text.substr(0, cookie.size()) != cookie) {
    throw usdErrorAt(SourceLoc(file, 1, 1), "not a usda text layer: expected '#usda 1.0' as the first line");
  }
  size_t end = text.find_first_of("\r\n");
  std::string_view version = text.substr(cookie.size(), end == std::string_view::npos ? end : end - cookie.size());
  while (!version.empty() && (version.back() == ' ' || version.back() == '\t')) version.remove_suffix(1);
  if (version.empty() || !std::all_of(version.begin(), version.end(), [](char c) { return (c >= '0' && c <= '9') || c == '.'; }))
    throw usdErrorAt(SourceLoc(file, 1, 7), "expected a version such as 1.0 after '#usda', found '" +
                                               std::string(version.substr(0, 40)) + "'");
  if (end == std::string_view::npos) return text.size();
  return end;  // the lexer sees the newline and counts it
}

bool isSpecifierWord(const Token& t) { return t.isWord("def") || t.isWord("over") || t.isWord("class"); }

}  // namespace

NestingGuard::NestingGuard(UsdaParser& parser, const char* what) : parser_(parser) {
  if (++parser_.nesting_ > parser_.limits_.maxNesting) {
    --parser_.nesting_;
    parser_.fail(parser_.tok_, std::string(what) + " nested deeper than the limit of " +
                                   std::to_string(parser_.limits_.maxNesting) + " levels");
  }
}

UsdaParser::UsdaParser(std::string_view text, const std::string& identifier, const ReadLimits& limits)
    : lexer_(text.substr(std::min(text.size(), checkHeader(text, FileName(identifier)))), FileName(identifier), 1),
      limits_(limits),
      file_(lexer_.file()) {
  layer_.identifier = identifier;
  layer_.format = "usda";
}

// ---- tokens ------------------------------------------------------------------

void UsdaParser::advance() {
  if (hasPeek_) {
    tok_ = peek_;
    hasPeek_ = false;
  } else {
    tok_ = lexer_.next();
  }
}

const Token& UsdaParser::peek() {
  if (!hasPeek_) {
    peek_ = lexer_.next();
    hasPeek_ = true;
  }
  return peek_;
}

void UsdaParser::fail(const Token& at, const std::string& message) const {
  throw usdErrorAt(lexer_.locOf(at), message);
}

std::string UsdaParser::describe(const Token& token) {
  auto clip = [](std::string_view s) {
    return s.size() > 40 ? std::string(s.substr(0, 40)) + "..." : std::string(s);
  };
  switch (token.kind) {
    case TokenKind::End: return "the end of the file";
    case TokenKind::Identifier: return "'" + clip(token.text) + "'";
    case TokenKind::Number: return "the number " + clip(token.text);
    case TokenKind::String: return "the string \"" + clip(token.text) + "\"";
    case TokenKind::Asset: return "the asset path @" + clip(token.text) + "@";
    case TokenKind::Path: return "the path <" + clip(token.text) + ">";
    case TokenKind::Punct: return "'" + std::string(token.text) + "'";
  }
  return "?";
}

void UsdaParser::expected(const std::string& what) const { fail(tok_, "expected " + what + ", found " + describe(tok_)); }

void UsdaParser::expectPunct(char c, const char* context) {
  if (!tok_.is(c)) expected(std::string("'") + c + "' " + context);
  advance();
}

std::string UsdaParser::expectString(const char* what) {
  if (tok_.kind != TokenKind::String) expected(what);
  std::string s = decodeString(tok_);
  advance();
  return s;
}

std::string UsdaParser::expectIdentifier(const char* what) {
  if (tok_.kind != TokenKind::Identifier) expected(what);
  std::string s(tok_.text);
  advance();
  return s;
}

void UsdaParser::endStatement(char closer, const char* what) {
  if (tok_.is(';')) {
    advance();
    return;
  }
  if (tok_.kind == TokenKind::End || tok_.newlineBefore || tok_.is(closer)) return;
  expected(std::string("';' or a new line after ") + what);
}

bool UsdaParser::isListOpWord() const {
  return tok_.isWord("add") || tok_.isWord("prepend") || tok_.isWord("append") || tok_.isWord("delete") ||
         tok_.isWord("reorder");
}

// ---- structure -------------------------------------------------------------------

Layer UsdaParser::parse() {
  advance();
  Token start = tok_;
  start.line = 1;
  start.column = 1;
  Spec& root = newSpec("/", SpecType::PseudoRoot, start);
  if (tok_.is('(')) parseMetadataBlock(root, Owner::Layer);
  std::vector<std::string> rootPrims;
  while (tok_.kind != TokenKind::End) {
    if (tok_.isWord("reorder") && peek().isWord("rootPrims")) {
      advance();
      advance();
      expectPunct('=', "after 'reorder rootPrims'");
      root.fields[field::kPrimOrder] = Value::textArray(Kind::TokenVector, parseNameList());
      endStatement('\0', "the statement");
      continue;
    }
    if (!isSpecifierWord(tok_)) expected("'def', 'over' or 'class' to start a prim");
    parsePrim("/", rootPrims);
  }
  if (!rootPrims.empty()) root.fields[field::kPrimChildren] = Value::textArray(Kind::TokenVector, std::move(rootPrims));
  return std::move(layer_);
}

Spec& UsdaParser::newSpec(const std::string& path, SpecType type, const Token& at) {
  if (layer_.specs.size() >= limits_.maxSpecs)
    fail(at, "more than " + std::to_string(limits_.maxSpecs) + " specs: the layer is too large to read");
  Spec& spec = layer_.specs[path];
  spec.type = type;
  spec.loc = lexer_.locOf(at);
  return spec;
}

void UsdaParser::parseMetadataBlock(Spec& spec, Owner owner) {
  NestingGuard guard(*this, "metadata");
  advance();  // '('
  while (!tok_.is(')')) {
    if (tok_.kind == TokenKind::End) expected("')' to close the metadata");
    parseMetadataEntry(spec, owner);
    endStatement(')', "the metadata entry");
  }
  advance();
}

void UsdaParser::parsePrim(const std::string& parentPath, std::vector<std::string>& siblings) {
  NestingGuard guard(*this, "prims");
  Token start = tok_;
  Specifier specifier = tok_.isWord("def") ? Specifier::Def : tok_.isWord("over") ? Specifier::Over : Specifier::Class;
  advance();
  std::string typeName;
  if (tok_.kind == TokenKind::Identifier) {
    typeName = std::string(tok_.text);
    advance();
    while (tok_.is('.')) {  // a Python-qualified type name ("Foo.Bar")
      advance();
      typeName += "." + expectIdentifier("a type name after '.'");
    }
  }
  if (tok_.kind != TokenKind::String) expected("the prim's name as a quoted string");
  Token nameToken = tok_;
  std::string name = decodeString(tok_);
  if (!path::isIdentifier(name)) fail(tok_, "'" + name + "' is not a valid prim name");
  advance();
  std::string primPath = path::child(parentPath, name);
  if (const Spec* existing = layer_.spec(primPath))
    fail(nameToken, "duplicate prim " + path::stripVariants(primPath) + " (first defined at " + existing->loc.str() + ")");
  Spec& spec = newSpec(primPath, SpecType::Prim, start);
  siblings.push_back(name);
  spec.fields[field::kSpecifier] = Value::specifier(specifier);
  if (!typeName.empty()) spec.fields[field::kTypeName] = Value::text(Kind::Token, typeName);
  std::string parentAnchor = std::move(anchor_);
  anchor_ = path::stripVariants(primPath);
  if (tok_.is('(')) parseMetadataBlock(spec, Owner::Prim);
  expectPunct('{', "to open the prim's contents");
  parseContents(primPath, spec);
  advance();  // '}'
  anchor_ = std::move(parentAnchor);
  endStatement('}', "the prim");
}

// The contents of a prim or variant between braces, up to the closing '}'
// (left as the current token).
void UsdaParser::parseContents(const std::string& primPath, Spec& spec) {
  std::vector<std::string> children, properties, variantSets;
  while (!tok_.is('}')) {
    if (tok_.kind == TokenKind::End) expected("'}' to close " + path::stripVariants(primPath));
    if (isSpecifierWord(tok_)) {
      parsePrim(primPath, children);
    } else if (tok_.isWord("variantSet") && peek().kind == TokenKind::String) {
      parseVariantSet(primPath, variantSets);
    } else if (tok_.isWord("reorder") && (peek().isWord("nameChildren") || peek().isWord("properties"))) {
      advance();
      const char* key = tok_.isWord("nameChildren") ? field::kPrimOrder : field::kPropertyOrder;
      advance();
      expectPunct('=', "after the reorder statement's name");
      spec.fields[key] = Value::textArray(Kind::TokenVector, parseNameList());
      endStatement('}', "the reorder statement");
    } else {
      parseProperty(primPath, properties);
      endStatement('}', "the property");
    }
  }
  if (!children.empty()) spec.fields[field::kPrimChildren] = Value::textArray(Kind::TokenVector, std::move(children));
  if (!properties.empty()) spec.fields[field::kProperties] = Value::textArray(Kind::TokenVector, std::move(properties));
  if (!variantSets.empty())
    spec.fields[field::kVariantSetChildren] = Value::textArray(Kind::TokenVector, std::move(variantSets));
}

void UsdaParser::parseVariantSet(const std::string& primPath, std::vector<std::string>& setNames) {
  NestingGuard guard(*this, "variant sets");
  Token start = tok_;
  advance();  // variantSet
  Token nameToken = tok_;
  std::string setName = decodeString(tok_);
  if (!path::isIdentifier(setName)) fail(tok_, "'" + setName + "' is not a valid variant set name");
  advance();
  std::string setPath = path::variantSet(primPath, setName);
  if (layer_.spec(setPath)) fail(nameToken, "duplicate variant set '" + setName + "'");
  expectPunct('=', "after the variant set's name");
  expectPunct('{', "to open the variant set");
  Spec& setSpec = newSpec(setPath, SpecType::VariantSet, start);
  setNames.push_back(setName);
  std::vector<std::string> variants;
  while (!tok_.is('}')) {
    if (tok_.kind != TokenKind::String) expected("a variant name as a quoted string, or '}'");
    Token variantToken = tok_;
    std::string variantName = decodeString(tok_);
    // Variant names may also hold '|', '-' and '.', and may start with a digit.
    bool valid = !variantName.empty() && std::all_of(variantName.begin(), variantName.end(), [](char c) {
      auto u = static_cast<unsigned char>(c);
      return std::isalnum(u) || c == '_' || c == '|' || c == '-' || c == '.' || u >= 0x80;
    });
    if (!valid) fail(tok_, "'" + variantName + "' is not a valid variant name");
    advance();
    std::string variantPath = path::variant(primPath, setName, variantName);
    if (layer_.spec(variantPath)) fail(variantToken, "duplicate variant '" + variantName + "' in set '" + setName + "'");
    Spec& variantSpec = newSpec(variantPath, SpecType::Variant, variantToken);
    variants.push_back(variantName);
    if (tok_.is('(')) parseMetadataBlock(variantSpec, Owner::Prim);
    expectPunct('{', "to open the variant's contents");
    parseContents(variantPath, variantSpec);
    advance();
  }
  advance();
  setSpec.fields[field::kVariantChildren] = Value::textArray(Kind::TokenVector, std::move(variants));
  endStatement('}', "the variant set");
}

Spec& UsdaParser::propertySpec(const std::string& primPath, const std::string& name, SpecType type,
                               const Token& at, std::vector<std::string>& properties) {
  std::string propPath = path::property(primPath, name);
  auto it = layer_.specs.find(propPath);
  if (it != layer_.specs.end()) {
    if (it->second.type != type)
      fail(at, "'" + name + "' is declared both as an attribute and as a relationship (first at " +
                   it->second.loc.str() + ")");
    return it->second;
  }
  properties.push_back(name);
  return newSpec(propPath, type, at);
}

void UsdaParser::parseProperty(const std::string& primPath, std::vector<std::string>& properties) {
  Token start = tok_;
  std::string listOp;
  if (isListOpWord() && peek().kind == TokenKind::Identifier) {
    listOp = std::string(tok_.text);
    advance();
  }
  bool custom = false;
  if (tok_.isWord("custom") && peek().kind == TokenKind::Identifier) {
    custom = true;
    advance();
  }
  if (tok_.isWord("rel") || (tok_.isWord("varying") && peek().isWord("rel"))) {
    parseRelationship(primPath, listOp, custom, properties, start);
  } else {
    parseAttribute(primPath, listOp, custom, properties, start);
  }
}

void UsdaParser::parseRelationship(const std::string& primPath, const std::string& listOp, bool custom,
                                   std::vector<std::string>& properties, const Token& start) {
  bool varying = tok_.isWord("varying");
  if (varying) advance();
  advance();  // rel
  Token nameToken = tok_;
  std::string name = expectIdentifier("the relationship's name");
  if (!path::isNamespacedIdentifier(name)) fail(nameToken, "'" + name + "' is not a valid relationship name");
  Spec& spec = propertySpec(primPath, name, SpecType::Relationship, start, properties);
  spec.fields[field::kCustom] = Value::scalar(Kind::Bool, {custom ? 1.0 : 0.0});
  spec.fields[field::kVariability] = Value::variability(varying ? Variability::Varying : Variability::Uniform);
  auto targets = [&]() -> ListOp<std::string>& {
    Value& v = spec.fields[field::kTargetPaths];
    if (!v.textListOp) {
      v.kind = Kind::PathListOp;
      v.textListOp = std::make_shared<ListOp<std::string>>();
    }
    return *v.textListOp;
  };
  if (tok_.is('[')) {  // rel name[</target>]: one target, the old form
    advance();
    std::string target = parsePath(false);
    expectPunct(']', "after the relationship target");
    auto& op = targets();
    op.isExplicit = op.isExplicit || listOp.empty();
    (op.isExplicit ? op.explicitItems : op.appendedItems).push_back(target);
    return;
  }
  if (tok_.is('.')) {
    advance();
    if (tok_.isWord("default")) {
      advance();
      expectPunct('=', "after '.default'");
      spec.fields[field::kDefault] = Value::textArray(Kind::PathVector, {parsePath(false)});
      return;
    }
    if (tok_.isWord("timeSamples")) fail(tok_, "time-sampled relationships are not supported");
    expected("'default' after '.'");
  }
  if (tok_.is('=')) {
    advance();
    setListOpItems(targets(), listOp, parsePathList(true, false));
  } else if (!listOp.empty()) {
    expected("'=' and the targets after '" + listOp + " rel " + name + "'");
  }
  if (tok_.is('(')) parseMetadataBlock(spec, Owner::Relationship);
}

void UsdaParser::parseAttribute(const std::string& primPath, const std::string& listOp, bool custom,
                                std::vector<std::string>& properties, const Token& start) {
  Variability variability = Variability::Varying;
  if (tok_.isWord("uniform") || tok_.isWord("config")) {
    variability = Variability::Uniform;
    advance();
  }
  Token typeToken = tok_;
  std::string typeName = expectIdentifier("an attribute type, a prim, 'rel' or 'variantSet'");
  if (tok_.is('[')) {
    advance();
    expectPunct(']', "to close the array type");
    typeName += "[]";
  }
  std::optional<ValueType> type = valueTypeForName(typeName);
  bool opaque = typeName == "opaque" || typeName == "group";
  bool pathExpression = typeName == "pathExpression";
  if (!type && !opaque && !pathExpression) {
    std::string base = typeName.substr(0, typeName.find('['));
    fail(typeToken, "unknown attribute type '" + base + "'" + text::didYouMean(base, valueTypeNames()));
  }
  if (pathExpression) type = ValueType{Kind::String, false};
  Token nameToken = tok_;
  std::string name = expectIdentifier("the attribute's name");
  if (!path::isNamespacedIdentifier(name)) fail(nameToken, "'" + name + "' is not a valid attribute name");
  Spec& spec = propertySpec(primPath, name, SpecType::Attribute, start, properties);
  if (const Value* existing = spec.field(field::kTypeName); existing && existing->asString() != typeName)
    fail(typeToken, "attribute '" + name + "' is declared as " + existing->asString() + " at " + spec.loc.str() +
                        " and as " + typeName + " here");
  spec.fields[field::kTypeName] = Value::text(Kind::Token, typeName);
  // A second declaration (`.connect`, `.timeSamples`) keeps the first one's qualifiers.
  if (custom || !spec.fields.count(field::kCustom)) spec.fields[field::kCustom] = Value::scalar(Kind::Bool, {custom ? 1.0 : 0.0});
  if (variability == Variability::Uniform || !spec.fields.count(field::kVariability))
    spec.fields[field::kVariability] = Value::variability(variability);
  auto setOnce = [&](const char* key, Value value, const Token& at) {
    if (spec.fields.count(key)) fail(at, "attribute '" + name + "' has a second " + key + " value");
    spec.fields[key] = std::move(value);
  };
  if (tok_.is('.')) {
    advance();
    Token what = tok_;
    if (tok_.isWord("connect")) {
      advance();
      expectPunct('=', "after '.connect'");
      Value& v = spec.fields[field::kConnectionPaths];
      if (!v.textListOp) {
        v.kind = Kind::PathListOp;
        v.textListOp = std::make_shared<ListOp<std::string>>();
      }
      setListOpItems(*v.textListOp, listOp, parsePathList(true, false));
      return;
    }
    if (!listOp.empty()) fail(start, "'" + listOp + "' applies to connections ('.connect') only");
    if (tok_.isWord("timeSamples")) {
      advance();
      expectPunct('=', "after '.timeSamples'");
      if (opaque) fail(what, typeName + " attributes hold no values");
      setOnce(field::kTimeSamples, parseTimeSamples(*type, typeName), what);
      return;
    }
    if (tok_.isWord("spline")) fail(tok_, "spline-valued attributes are not supported");
    expected("'connect' or 'timeSamples' after '.'");
  }
  if (!listOp.empty()) fail(start, "'" + listOp + "' applies to connections ('.connect') only");
  if (tok_.is('=')) {
    Token valueToken = peek();
    advance();
    if (opaque) fail(valueToken, typeName + " attributes hold no values");
    if (tok_.isWord("None")) {
      advance();
      setOnce(field::kDefault, Value::block(), valueToken);
    } else {
      setOnce(field::kDefault, parseTypedValue(*type, typeName), valueToken);
    }
  }
  if (tok_.is('(')) parseMetadataBlock(spec, Owner::Attribute);
}

// ---- entry point ---------------------------------------------------------------

Layer readUsdaLayer(std::string_view text, const std::string& identifier, const ReadLimits& limits) {
  if (text.size() > limits.maxFileBytes)
    throw usdErrorAt(SourceLoc(identifier, 0, 0), "the layer is " + std::to_string(text.size()) +
                                                       " bytes, beyond the limit of " +
                                                       std::to_string(limits.maxFileBytes));
  UsdaParser parser(text, identifier, limits);
  return parser.parse();
}

}  // namespace sdg::usd
