#include "usd/usda_lexer.h"

#include <cctype>

#include "usd/layer.h"

namespace sdg::usd {

namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }
bool identStart(char c) {
  auto u = static_cast<unsigned char>(c);
  return c == '_' || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || u >= 0x80;
}
bool identChar(char c) { return identStart(c) || isDigit(c); }

std::string describeChar(char c) {
  auto u = static_cast<unsigned char>(c);
  if (u < 0x20 || u == 0x7f) {
    static const char* kHex = "0123456789abcdef";
    return std::string("byte 0x") + kHex[u >> 4] + kHex[u & 15];
  }
  return std::string("'") + c + "'";
}

}  // namespace

UsdaLexer::UsdaLexer(std::string_view text, FileName file, int firstLine)
    : text_(text), file_(std::move(file)), line_(firstLine) {}

void UsdaLexer::fail(int line, int column, const std::string& message) const {
  throw usdErrorAt(SourceLoc(file_, line, column), message);
}

void UsdaLexer::skipSpaceAndComments(bool& sawNewline) {
  while (pos_ < text_.size()) {
    char c = text_[pos_];
    if (c == ' ' || c == '\t') {
      ++pos_;
    } else if (c == '\n') {
      newline(++pos_);
      sawNewline = true;
    } else if (c == '\r') {
      ++pos_;
      if (pos_ < text_.size() && text_[pos_] == '\n') ++pos_;
      newline(pos_);
      sawNewline = true;
    } else if (c == '#' || (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '/')) {
      while (pos_ < text_.size() && text_[pos_] != '\n' && text_[pos_] != '\r') ++pos_;
    } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '*') {
      int line = line_;
      int column = static_cast<int>(pos_ - lineStart_) + 1;
      pos_ += 2;
      while (true) {
        if (pos_ + 1 >= text_.size()) fail(line, column, "unterminated /* comment");
        if (text_[pos_] == '*' && text_[pos_ + 1] == '/') {
          pos_ += 2;
          break;
        }
        if (text_[pos_] == '\n') {
          sawNewline = true;
          newline(pos_ + 1);
        }
        ++pos_;
      }
    } else {
      return;
    }
  }
}

Token UsdaLexer::next() {
  Token token;
  skipSpaceAndComments(token.newlineBefore);
  token.line = line_;
  token.column = static_cast<int>(pos_ - lineStart_) + 1;
  token.offset = pos_;
  if (pos_ >= text_.size()) return token;  // End
  char c = text_[pos_];
  if (c == '"' || c == '\'') return lexString(token);
  if (c == '@') return lexAsset(token);
  if (c == '<') {
    size_t end = pos_ + 1;
    while (end < text_.size() && text_[end] != '>' && text_[end] != '<' && text_[end] != '\n' && text_[end] != '\r')
      ++end;
    if (end >= text_.size() || text_[end] != '>') fail(token.line, token.column, "unterminated path: expected '>'");
    token.kind = TokenKind::Path;
    token.text = text_.substr(pos_ + 1, end - pos_ - 1);
    pos_ = end + 1;
    return token;
  }
  if (isDigit(c) || ((c == '-' || c == '.') && pos_ + 1 < text_.size() &&
                     (isDigit(text_[pos_ + 1]) || (c == '-' && text_[pos_ + 1] == '.'))))
    return lexNumber(token);
  if (c == '-' && text_.substr(pos_, 4) == "-inf" && (pos_ + 4 >= text_.size() || !identChar(text_[pos_ + 4]))) {
    token.kind = TokenKind::Number;
    token.text = text_.substr(pos_, 4);
    pos_ += 4;
    return token;
  }
  if (identStart(c)) return lexIdentifier(token);
  switch (c) {
    case '=': case ',': case ':': case ';': case '.': case '[': case ']':
    case '(': case ')': case '{': case '}': case '&': case '-':
      token.kind = TokenKind::Punct;
      token.text = text_.substr(pos_, 1);
      ++pos_;
      return token;
    default:
      fail(token.line, token.column, "unexpected " + describeChar(c));
  }
}

Token UsdaLexer::lexString(Token token) {
  char quote = text_[pos_];
  token.kind = TokenKind::String;
  bool triple = text_.size() - pos_ >= 3 && text_[pos_ + 1] == quote && text_[pos_ + 2] == quote;
  token.tripleQuoted = triple;
  size_t start = pos_ + (triple ? 3 : 1);
  size_t i = start;
  while (true) {
    if (i >= text_.size()) fail(token.line, token.column, std::string("unterminated string: expected ") +
                                                              (triple ? std::string(3, quote) : std::string(1, quote)));
    char c = text_[i];
    if (c == '\\') {
      token.escaped = true;
      if (i + 1 < text_.size() && text_[i + 1] == '\n' && triple) newline(i + 2);
      i += 2;
      continue;
    }
    if (c == '\n' || c == '\r') {
      if (!triple) fail(token.line, token.column, std::string("unterminated string: expected ") + quote + " before the end of the line");
      if (c == '\r' && i + 1 < text_.size() && text_[i + 1] == '\n') ++i;
      newline(i + 1);
    } else if (c == quote) {
      if (!triple) break;
      if (text_.size() - i >= 3 && text_[i + 1] == quote && text_[i + 2] == quote) break;
    }
    ++i;
  }
  token.text = text_.substr(start, i - start);
  pos_ = i + (triple ? 3 : 1);
  return token;
}

Token UsdaLexer::lexAsset(Token token) {
  token.kind = TokenKind::Asset;
  if (text_.substr(pos_, 3) == "@@@") {
    token.tripleQuoted = true;
    size_t start = pos_ + 3;
    size_t i = start;
    while (true) {
      if (i >= text_.size() || text_[i] == '\n') fail(token.line, token.column, "unterminated asset path: expected '@@@'");
      if (text_[i] == '\\' && text_.substr(i + 1, 3) == "@@@") {
        token.escaped = true;
        i += 4;
        continue;
      }
      if (text_.substr(i, 3) == "@@@") {
        // "@@@a@@@@" ends with the last three '@' of the run.
        while (i + 3 < text_.size() && text_[i + 3] == '@') ++i;
        break;
      }
      ++i;
    }
    token.text = text_.substr(start, i - start);
    pos_ = i + 3;
    return token;
  }
  size_t end = pos_ + 1;
  while (end < text_.size() && text_[end] != '@' && text_[end] != '\n') ++end;
  if (end >= text_.size() || text_[end] != '@') fail(token.line, token.column, "unterminated asset path: expected '@'");
  token.text = text_.substr(pos_ + 1, end - pos_ - 1);
  pos_ = end + 1;
  return token;
}

Token UsdaLexer::lexNumber(Token token) {
  token.kind = TokenKind::Number;
  size_t i = pos_;
  if (text_[i] == '-') ++i;
  while (i < text_.size() && isDigit(text_[i])) ++i;
  if (i < text_.size() && text_[i] == '.') {
    ++i;
    while (i < text_.size() && isDigit(text_[i])) ++i;
  }
  if (i < text_.size() && (text_[i] == 'e' || text_[i] == 'E')) {
    size_t e = i + 1;
    if (e < text_.size() && (text_[e] == '+' || text_[e] == '-')) ++e;
    if (e < text_.size() && isDigit(text_[e])) {
      i = e;
      while (i < text_.size() && isDigit(text_[i])) ++i;
    }
  }
  if (i < text_.size() && identStart(text_[i]))
    fail(token.line, token.column, "malformed number '" + std::string(text_.substr(pos_, i - pos_ + 1)) + "'");
  token.text = text_.substr(pos_, i - pos_);
  pos_ = i;
  return token;
}

Token UsdaLexer::lexIdentifier(Token token) {
  token.kind = TokenKind::Identifier;
  size_t i = pos_;
  auto word = [&] {
    while (i < text_.size() && identChar(text_[i])) ++i;
  };
  word();
  // "a:b:c" (namespaced) or "a::b" (C++): a separator directly followed by a word.
  while (i + 1 < text_.size() && text_[i] == ':') {
    size_t sep = text_[i + 1] == ':' ? 2 : 1;
    if (i + sep >= text_.size() || !identStart(text_[i + sep])) break;
    i += sep;
    word();
  }
  token.text = text_.substr(pos_, i - pos_);
  pos_ = i;
  return token;
}

std::string decodeString(const Token& token) {
  if (!token.escaped) return std::string(token.text);
  std::string_view in = token.text;
  std::string out;
  out.reserve(in.size());
  if (token.kind == TokenKind::Asset) {  // only \@@@ is an escape in triple-@ asset paths
    for (size_t i = 0; i < in.size(); ++i) {
      if (in[i] == '\\' && in.substr(i + 1, 3) == "@@@") {
        out += "@@@";
        i += 3;
      } else {
        out += in[i];
      }
    }
    return out;
  }
  for (size_t i = 0; i < in.size(); ++i) {
    char c = in[i];
    if (c != '\\' || i + 1 >= in.size()) {
      out += c;
      continue;
    }
    char e = in[++i];
    switch (e) {
      case 'n': out += '\n'; break;
      case 't': out += '\t'; break;
      case 'r': out += '\r'; break;
      case 'a': out += '\a'; break;
      case 'b': out += '\b'; break;
      case 'f': out += '\f'; break;
      case 'v': out += '\v'; break;
      case '\n': break;  // a line continuation in a triple-quoted string
      case 'x': {
        int value = 0, digits = 0;
        while (digits < 2 && i + 1 < in.size() && std::isxdigit(static_cast<unsigned char>(in[i + 1]))) {
          char h = in[++i];
          value = value * 16 + (isDigit(h) ? h - '0' : (h | 0x20) - 'a' + 10);
          ++digits;
        }
        out += static_cast<char>(value);
        break;
      }
      default:
        if (e >= '0' && e <= '7') {
          int value = e - '0', digits = 1;
          while (digits < 3 && i + 1 < in.size() && in[i + 1] >= '0' && in[i + 1] <= '7') {
            value = value * 8 + (in[++i] - '0');
            ++digits;
          }
          out += static_cast<char>(value);
        } else {
          out += e;  // \\ \" \' and any other escaped character stand for themselves
        }
    }
  }
  return out;
}

}  // namespace sdg::usd
