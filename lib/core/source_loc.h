#pragma once
// Where something came from: a file (or a pseudo-file such as "--set #2"),
// a 1-based line and a 1-based column. Carried on every prim and attribute
// read from YAML so that errors found later can still point at the line.
#include <string>

namespace sdg {

struct SourceLoc {
  std::string file;
  int line = 0;    // 1-based; 0 = unknown
  int column = 0;  // 1-based; 0 = unknown

  bool known() const { return !file.empty(); }
  // "file:line:col", "file" when the position is unknown, "" when nothing is.
  std::string str() const;
  bool operator==(const SourceLoc&) const = default;
};

}  // namespace sdg
