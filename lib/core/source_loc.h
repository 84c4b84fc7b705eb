#pragma once
// Where something came from: a file (or a pseudo-file such as "--set #2"),
// a 1-based line and a 1-based column. Carried on every prim and attribute
// read from YAML so that errors found later can still point at the line.
#include <compare>
#include <memory>
#include <string>

namespace sdg {

// A file name that every location in the file shares: a document of
// 2,000,000 nodes must not hold 2,000,000 copies of a long path.
class FileName {
 public:
  FileName() = default;
  FileName(std::string name)  // NOLINT(google-explicit-constructor): a name is a name
      : name_(name.empty() ? nullptr : std::make_shared<const std::string>(std::move(name))) {}
  FileName(const char* name) : FileName(std::string(name)) {}  // NOLINT(google-explicit-constructor)

  const std::string& str() const {
    static const std::string kNone;
    return name_ ? *name_ : kNone;
  }
  operator const std::string&() const { return str(); }  // NOLINT(google-explicit-constructor)
  bool empty() const { return !name_; }

  friend bool operator==(const FileName& a, const FileName& b) { return a.str() == b.str(); }
  friend std::strong_ordering operator<=>(const FileName& a, const FileName& b) { return a.str() <=> b.str(); }

 private:
  std::shared_ptr<const std::string> name_;
};

struct SourceLoc {
  SourceLoc() = default;
  SourceLoc(FileName file, int line, int column) : file(std::move(file)), line(line), column(column) {}

  FileName file;
  int line = 0;    // 1-based; 0 = unknown
  int column = 0;  // 1-based; 0 = unknown
  // Where the file was referenced from, for values mounted from a smart
  // asset (scene_io/references.h); null for the scene's own values.
  std::shared_ptr<const SourceLoc> via;

  bool known() const { return !file.empty(); }
  // "file:line:col", "file:line" without a column, "file" when the position is unknown, "" when nothing is.
  std::string str() const;
  // "referenced from scene.yaml:12:7[, from ...]", or "" without a via.
  std::string referenceChain() const;
  bool operator==(const SourceLoc&) const = default;
};

}  // namespace sdg
