#pragma once
// The tokens of a .usda text layer: identifiers (plain, ':'-namespaced and
// C++ '::' ones; keywords are identifiers the parser recognises), numbers,
// quoted strings (single, double and triple quotes, with escapes), asset
// paths (@...@ and @@@...@@@), path references (<...>) and punctuation.
// Comments (#, //, /* */) and whitespace are skipped; a newline is not a
// token but marks the token after it (`newlineBefore`), which is how the
// parser tells statements apart. Tokens point into the text: the lexer
// allocates nothing except for strings with escapes, decoded on demand.
#include <cstdint>
#include <string>
#include <string_view>

#include "core/source_loc.h"

namespace sdg::usd {

enum class TokenKind : uint8_t { End, Identifier, Number, String, Asset, Path, Punct };

struct Token {
  TokenKind kind = TokenKind::End;
  std::string_view text;  // identifiers, numbers: as written; strings, assets, paths: between the delimiters
  int line = 0;
  int column = 0;
  bool newlineBefore = false;  // a newline separates this token from the previous one
  bool escaped = false;        // a string or triple-@ asset whose text holds escapes (see decodeString)
  bool tripleQuoted = false;   // a string or asset written with triple delimiters

  bool is(char punct) const { return kind == TokenKind::Punct && text.size() == 1 && text[0] == punct; }
  bool isWord(std::string_view word) const { return kind == TokenKind::Identifier && text == word; }
};

class UsdaLexer {
 public:
  // `text` starts after the "#usda 1.0" line; `firstLine` is its line number.
  UsdaLexer(std::string_view text, FileName file, int firstLine);

  Token next();
  SourceLoc locOf(const Token& token) const { return SourceLoc(file_, token.line, token.column); }
  const FileName& file() const { return file_; }

 private:
  [[noreturn]] void fail(int line, int column, const std::string& message) const;
  void skipSpaceAndComments(bool& sawNewline);
  Token lexString(Token token);
  Token lexAsset(Token token);
  Token lexNumber(Token token);
  Token lexIdentifier(Token token);
  void newline(size_t nextPos) {
    ++line_;
    lineStart_ = nextPos;
  }

  std::string_view text_;
  FileName file_;
  size_t pos_ = 0;
  size_t lineStart_ = 0;
  int line_ = 1;
};

// The value of a string or asset token: the text itself, or with its
// escapes (\n, \t, \", \\, \xHH, octal, ...) replaced when `escaped`.
std::string decodeString(const Token& token);

}  // namespace sdg::usd
