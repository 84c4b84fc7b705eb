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
  size_t offset = 0;      // where the token starts in the lexer's text
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

  // Direct access for scanners that read long runs of numbers without
  // making tokens (usda_values.cpp): the text, and the position as a
  // (offset, line, line start) state that can be taken at a token and restored.
  struct State {
    size_t pos;
    size_t lineStart;
    int line;
  };
  std::string_view text() const { return text_; }
  static State stateAt(const Token& token) {
    return State{token.offset, token.offset - static_cast<size_t>(token.column - 1), token.line};
  }
  void restore(const State& state) {
    pos_ = state.pos;
    lineStart_ = state.lineStart;
    line_ = state.line;
  }

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
