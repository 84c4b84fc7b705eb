#include "stage/path.h"

namespace sdg::path {

bool isIdentifier(std::string_view name) {
  if (name.empty()) return false;
  auto alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  auto digit = [](char c) { return c >= '0' && c <= '9'; };
  if (!alpha(name[0])) return false;
  for (char c : name)
    if (!alpha(c) && !digit(c)) return false;
  return true;
}

std::string whyInvalid(std::string_view path) {
  if (path.empty()) return "a prim path must not be empty";
  if (path.size() > kMaxPathLength)
    return "a prim path is limited to " + std::to_string(kMaxPathLength) + " characters, this one has " +
           std::to_string(path.size());
  if (path[0] != '/') return "a prim path must be absolute (start with '/')";
  if (path == "/") return "'/' is the pseudo-root; name a prim below it, e.g. /Root";
  if (path.back() == '/') return "a prim path must not end with '/'";
  size_t components = 0;
  size_t start = 1;
  while (start <= path.size()) {
    size_t slash = path.find('/', start);
    if (slash == std::string_view::npos) slash = path.size();
    std::string_view component = path.substr(start, slash - start);
    if (component.empty()) return "a prim path must not contain '//'";
    if (!isIdentifier(component))
      return "prim name '" + std::string(component.substr(0, 64)) +
             "' is not an identifier (letters, digits and '_', not starting with a digit)";
    if (++components > kMaxDepth)
      return "prims may be nested at most " + std::to_string(kMaxDepth) + " levels deep";
    start = slash + 1;
  }
  return {};
}

std::string_view parent(std::string_view path) {
  if (path.size() <= 1) return {};
  size_t slash = path.rfind('/');
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

std::string_view name(std::string_view path) {
  size_t slash = path.rfind('/');
  return slash == std::string_view::npos ? path : path.substr(slash + 1);
}

bool isAtOrBelow(std::string_view path, std::string_view ancestor) {
  if (ancestor == "/") return !path.empty() && path[0] == '/';
  if (path.size() < ancestor.size() || path.substr(0, ancestor.size()) != ancestor) return false;
  return path.size() == ancestor.size() || path[ancestor.size()] == '/';
}

size_t depth(std::string_view path) {
  size_t n = 0;
  for (char c : path) n += c == '/';
  return path == "/" ? 0 : n;
}

}  // namespace sdg::path
