#pragma once
// The .usda parser's internals, shared by its two source files:
// usda_reader.cpp (the layer's structure: metadata blocks, prims,
// properties, variant sets) and usda_values.cpp (values: typed attribute
// values and arrays, time samples, dictionaries, list ops, references,
// untyped metadata). Recursive descent over UsdaLexer's tokens, one token
// of lookahead (two where a list-op prefix must be told from a name).
// Every nesting level is counted against ReadLimits::maxNesting so hostile
// text cannot exhaust the stack.
#include <string>
#include <string_view>
#include <vector>

#include "usd/layer.h"
#include "usd/usda_lexer.h"

namespace sdg::usd {

class UsdaParser {
 public:
  UsdaParser(std::string_view text, const std::string& identifier, const ReadLimits& limits);
  Layer parse();

 private:
  friend class NestingGuard;
  enum class Owner { Layer, Prim, Attribute, Relationship };

  // ---- tokens (usda_reader.cpp)
  void advance();
  const Token& peek();
  [[noreturn]] void fail(const Token& at, const std::string& message) const;
  [[noreturn]] void expected(const std::string& what) const;  // "expected <what>, found <tok_>"
  static std::string describe(const Token& token);
  void expectPunct(char c, const char* context);
  std::string expectString(const char* what);
  std::string expectIdentifier(const char* what);
  // After a statement: ';', a newline, or the closing `closer`.
  void endStatement(char closer, const char* what);
  bool isListOpWord() const;
  SourceLoc here() const { return lexer_.locOf(tok_); }

  // ---- structure (usda_reader.cpp)
  Spec& newSpec(const std::string& path, SpecType type, const Token& at);
  void parseMetadataBlock(Spec& spec, Owner owner);
  void parseMetadataEntry(Spec& spec, Owner owner);
  void parsePrim(const std::string& parentPath, std::vector<std::string>& siblings);
  void parseContents(const std::string& primPath, Spec& spec);
  void parseVariantSet(const std::string& primPath, std::vector<std::string>& setNames);
  void parseProperty(const std::string& primPath, std::vector<std::string>& properties);
  void parseRelationship(const std::string& primPath, const std::string& listOp, bool custom,
                         std::vector<std::string>& properties, const Token& start);
  void parseAttribute(const std::string& primPath, const std::string& listOp, bool custom,
                      std::vector<std::string>& properties, const Token& start);
  Spec& propertySpec(const std::string& primPath, const std::string& name, SpecType type, const Token& at,
                     std::vector<std::string>& properties);

  // ---- values (usda_values.cpp)
  Value parseTypedValue(ValueType type, const std::string& typeName);
  void parseElement(Kind kind, std::vector<double>& numbers, std::vector<std::string>& strings);
  double parseNumber(Kind kind);
  bool scanNumberArray(Kind kind, std::vector<double>& numbers, uint64_t& count);
  Value parseTimeSamples(ValueType type, const std::string& typeName);
  Value parseTypedDictionary();
  Value parseMetadataValue(const std::string& key, const Token& keyToken);
  Value parseGenericValue();
  std::vector<std::string> parsePathList(bool allowNone, bool primPathsOnly);
  std::vector<std::string> parseNameList();
  std::vector<Reference> parseReferenceList(bool payload);
  LayerOffset parseLayerOffsetEntries(Reference* reference);
  void parseSubLayers(Spec& pseudoRoot);
  Value parseStringDictionary();
  Value parseRelocates();
  std::string parsePath(bool primPathOnly);

  UsdaLexer lexer_;
  Token tok_;
  Token peek_;
  bool hasPeek_ = false;
  Layer layer_;
  ReadLimits limits_;
  FileName file_;
  uint32_t nesting_ = 0;
  // The prim that relative paths are anchored at (variant selections
  // stripped), computed once per prim: paths in a long list reuse it.
  std::string anchor_ = "/";
};

// Counts one nesting level for its lifetime; throws past the limit.
class NestingGuard {
 public:
  NestingGuard(UsdaParser& parser, const char* what);
  ~NestingGuard() { --parser_.nesting_; }
  NestingGuard(const NestingGuard&) = delete;
  NestingGuard& operator=(const NestingGuard&) = delete;

 private:
  UsdaParser& parser_;
};

// Sets one list of a list op, as Sdf does: `op` is "" (the explicit list),
// "add", "prepend", "append", "delete" or "reorder"; a second statement for
// the same list replaces the first.
template <class T>
void setListOpItems(ListOp<T>& listOp, const std::string& op, std::vector<T> items) {
  if (op.empty()) {
    listOp.isExplicit = true;
    listOp.explicitItems = std::move(items);
  } else if (op == "add") {
    listOp.addedItems = std::move(items);
  } else if (op == "prepend") {
    listOp.prependedItems = std::move(items);
  } else if (op == "append") {
    listOp.appendedItems = std::move(items);
  } else if (op == "delete") {
    listOp.deletedItems = std::move(items);
  } else {
    listOp.orderedItems = std::move(items);
  }
}

}  // namespace sdg::usd
