#include "usd/sdf_path.h"

namespace sdg::usd::path {

static bool identStart(unsigned char c) { return c == '_' || (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c >= 0x80; }
static bool identChar(unsigned char c) { return identStart(c) || (c >= '0' && c <= '9'); }

std::string child(std::string_view parent, std::string_view name) {
  std::string out(parent);
  if (out != "/" && !out.empty() && out.back() != '}') out += '/';
  out += name;
  return out;
}

std::string property(std::string_view prim, std::string_view name) {
  std::string out(prim);
  out += '.';
  out += name;
  return out;
}

std::string variantSet(std::string_view prim, std::string_view set) {
  return std::string(prim) + "{" + std::string(set) + "=}";
}

std::string variant(std::string_view prim, std::string_view set, std::string_view selection) {
  return std::string(prim) + "{" + std::string(set) + "=" + std::string(selection) + "}";
}

// The index of the first '.' or '[' outside variant braces (the start of
// the property part), or npos.
static size_t propertyStart(std::string_view path) {
  int braces = 0;
  for (size_t i = 0; i < path.size(); ++i) {
    char c = path[i];
    if (c == '{') ++braces;
    else if (c == '}') --braces;
    else if (braces == 0 && (c == '.' || c == '[')) return i;
  }
  return std::string_view::npos;
}

std::string_view primPart(std::string_view path) {
  size_t dot = propertyStart(path);
  return dot == std::string_view::npos ? path : path.substr(0, dot);
}

std::string_view propertyName(std::string_view path) {
  size_t dot = propertyStart(path);
  if (dot == std::string_view::npos || path[dot] != '.') return {};
  std::string_view rest = path.substr(dot + 1);
  size_t end = rest.find_first_of(".[");
  return end == std::string_view::npos ? rest : rest.substr(0, end);
}

std::string parent(std::string_view primPath) {
  if (primPath.size() <= 1) return "/";
  if (primPath.back() == '}') {  // "/A{v=x}" -> "/A"
    size_t open = primPath.rfind('{');
    return std::string(primPath.substr(0, open));
  }
  size_t cut = primPath.size();
  while (cut > 0 && primPath[cut - 1] != '/' && primPath[cut - 1] != '}') --cut;
  if (cut == 0) return "/";
  if (primPath[cut - 1] == '}') return std::string(primPath.substr(0, cut));  // "/A{v=x}B" -> "/A{v=x}"
  if (cut == 1) return "/";
  return std::string(primPath.substr(0, cut - 1));
}

std::string_view name(std::string_view primPath) {
  size_t cut = primPath.size();
  while (cut > 0 && primPath[cut - 1] != '/' && primPath[cut - 1] != '}') --cut;
  return primPath.substr(cut);
}

int depth(std::string_view primPath) {
  std::string stripped = stripVariants(primPart(primPath));
  int n = 0;
  for (char c : stripped)
    if (c == '/') ++n;
  return stripped == "/" ? 0 : n;
}

bool hasVariants(std::string_view path) { return path.find('{') != std::string_view::npos; }

std::string stripVariants(std::string_view path) {
  std::string out;
  out.reserve(path.size());
  size_t i = 0;
  while (i < path.size()) {
    char c = path[i];
    if (c == '[') {  // a target path inside: copied as it is
      out.append(path.substr(i));
      break;
    }
    if (c == '{') {
      size_t close = path.find('}', i);
      if (close == std::string_view::npos) close = path.size() - 1;
      i = close + 1;
      // A name right after a selection is a child: it needs a separator.
      if (i < path.size() && path[i] != '.' && path[i] != '{' && path[i] != '[') out += '/';
      continue;
    }
    out += c;
    ++i;
  }
  return out;
}

bool hasPrefix(std::string_view path, std::string_view prefix) {
  if (prefix == "/") return !path.empty() && path[0] == '/';
  if (path.size() < prefix.size() || path.substr(0, prefix.size()) != prefix) return false;
  if (path.size() == prefix.size()) return true;
  char next = path[prefix.size()];
  return next == '/' || next == '.' || next == '{' || next == '[' || prefix.back() == '}';
}

std::string replacePrefix(std::string_view path, std::string_view oldPrefix, std::string_view newPrefix) {
  if (oldPrefix == "/") {
    // "/A" under "/" onto "/X" -> "/X/A".
    return newPrefix == "/" ? std::string(path) : child(newPrefix, path.substr(1));
  }
  std::string_view rest = path.substr(oldPrefix.size());
  if (newPrefix == "/") {
    if (rest.empty()) return "/";
    if (rest[0] == '/') return std::string(rest);
    return "/" + std::string(rest);  // a name after a stripped selection
  }
  std::string out(newPrefix);
  if (!rest.empty() && oldPrefix.back() == '}' && rest[0] != '.' && rest[0] != '{' && newPrefix.back() != '}')
    out += '/';  // "/A{v=x}" + "B" moving onto a plain prim path
  out += rest;
  return out;
}

std::string makeAbsolute(std::string_view anchor, std::string_view p) {
  if (!p.empty() && p[0] == '/') return std::string(p);
  std::string base(anchor);
  size_t i = 0;
  while (p.substr(i, 2) == ".." && (i + 2 == p.size() || p[i + 2] == '/' || p[i + 2] == '.')) {
    if (base == "/") return "";
    // Up one prim, in place: cut at the last separator.
    size_t cut = base.find_last_of("/}");
    if (cut == std::string::npos) return "";
    if (base[cut] == '}') {
      size_t open = base.rfind('{', cut);
      base.resize(open == std::string::npos ? cut : open);
    } else {
      base.resize(cut == 0 ? 1 : cut);
    }
    i += 2;
    if (i < p.size() && p[i] == '/') ++i;
  }
  std::string_view rest = p.substr(i);
  if (rest.empty()) return base;
  if (rest[0] != '.' && base != "/" && base.back() != '}') base += '/';
  base += rest;
  return base;
}


bool isIdentifier(std::string_view name) {
  if (name.empty() || !identStart(static_cast<unsigned char>(name[0]))) return false;
  for (char c : name)
    if (!identChar(static_cast<unsigned char>(c))) return false;
  return true;
}

bool isNamespacedIdentifier(std::string_view name) {
  size_t start = 0;
  while (true) {
    size_t colon = name.find(':', start);
    if (!isIdentifier(name.substr(start, colon == std::string_view::npos ? std::string_view::npos : colon - start)))
      return false;
    if (colon == std::string_view::npos) return true;
    start = colon + 1;
  }
}

bool isValidPath(std::string_view p) {
  if (p.empty()) return false;
  size_t i = 0;
  bool absolute = p[0] == '/';
  if (absolute) {
    if (p.size() == 1) return true;
    i = 1;
  } else {
    while (p.substr(i, 2) == "..") {  // leading "../" steps
      i += 2;
      if (i == p.size()) return true;
      if (p[i] == '.') break;  // "..": a property of the parent
      if (p[i] != '/') return false;
      ++i;
    }
  }
  // Prim names, each perhaps followed by variant selections.
  while (i < p.size() && p[i] != '.') {
    size_t end = i;
    while (end < p.size() && identChar(static_cast<unsigned char>(p[end]))) ++end;
    if (end == i || !identStart(static_cast<unsigned char>(p[i]))) return false;
    i = end;
    while (i < p.size() && p[i] == '{') {
      size_t close = p.find('}', i);
      if (close == std::string_view::npos || p.substr(i, close - i).find('=') == std::string_view::npos) return false;
      i = close + 1;
    }
    if (i < p.size() && p[i] == '/') {
      if (++i == p.size()) return false;
    } else if (i < p.size() && p[i] != '.' && p[i - 1] != '}') {
      return false;
    }
  }
  if (i == p.size()) return true;
  // A property, perhaps with one target path and a name after it.
  size_t end = ++i;
  while (end < p.size() && (identChar(static_cast<unsigned char>(p[end])) || p[end] == ':')) ++end;
  if (!isNamespacedIdentifier(p.substr(i, end - i))) return false;
  i = end;
  if (i < p.size() && p[i] == '[') {
    if (p.back() == ']') return p.size() - i > 2 && p.substr(i + 1, p.size() - i - 2).find('[') == std::string_view::npos &&
                                isValidPath(p.substr(i + 1, p.size() - i - 2));
    size_t close = p.find(']', i);
    if (close == std::string_view::npos) return false;
    std::string_view target = p.substr(i + 1, close - i - 1);
    if (target.find('[') != std::string_view::npos || !isValidPath(target)) return false;
    i = close + 1;
    if (i == p.size() || p[i] != '.') return false;
    return isNamespacedIdentifier(p.substr(i + 1));
  }
  return i == p.size();
}

bool isAbsolutePrimPath(std::string_view path) {
  if (path == "/") return true;
  if (path.empty() || path[0] != '/') return false;
  size_t start = 1;
  while (start <= path.size()) {
    size_t slash = path.find('/', start);
    std::string_view part = path.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
    if (!isIdentifier(part)) return false;
    if (slash == std::string_view::npos) return true;
    start = slash + 1;
  }
  return false;
}

}  // namespace sdg::usd::path
