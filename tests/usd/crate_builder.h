#pragma once
// Hand-crafting small crate files for tests: the test lays out the tokens,
// paths, value bytes and value reps itself (as the format spells them), and
// the builder frames them into a bootstrap, structural sections and a table
// of contents. It is not a Layer writer: it knows nothing of value types,
// so the tests say byte for byte what each version of the format stores.
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "usd/crate_file.h"

namespace sdg::usd::test {

// A value rep: type, flags, payload.
uint64_t rep(CrateType type, uint64_t payload, bool isArray = false, bool isInlined = false,
             bool isCompressed = false);
inline uint64_t inlined(CrateType type, uint32_t payload) { return rep(type, payload, false, true); }

class CrateBuilder {
 public:
  explicit CrateBuilder(uint8_t minor = 8, uint8_t patch = 0);

  uint32_t token(const std::string& s);
  uint32_t string(const std::string& s);  // an entry of the string table
  uint32_t path(const std::string& p);    // adds the path (and its ancestors) to the tree
  uint32_t emptyPath();                   // the empty path: in the table, not in the tree

  // The out-of-line value area (between the bootstrap and the sections).
  uint64_t tell() const { return bytes_.size(); }
  template <class T>
  uint64_t put(const T& v) {
    uint64_t at = tell();
    const auto* p = reinterpret_cast<const uint8_t*>(&v);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
    return at;
  }
  template <class T>
  uint64_t putAll(const std::vector<T>& vs) {
    uint64_t at = tell();
    for (const T& v : vs) put(v);
    return at;
  }
  uint64_t putBytes(std::span<const uint8_t> b) {
    uint64_t at = tell();
    bytes_.insert(bytes_.end(), b.begin(), b.end());
    return at;
  }
  // A compressed integer stream: byte count, then the framed coding.
  template <class Int>
  uint64_t putCompressed(const std::vector<Int>& values);
  void align(size_t n) {
    while (bytes_.size() % n) bytes_.push_back(0);
  }

  // A field: its name and value rep. Returns the field index.
  uint32_t field(const std::string& name, uint64_t valueRep);
  // A spec at `path` holding `fields` (a new field set).
  void spec(const std::string& path, SpecType type, const std::vector<uint32_t>& fields);

  // The whole file. Sections are written in the order of `order` (all six
  // by default); the byte ranges of each are in sections() afterwards.
  std::vector<uint8_t> finish();
  const std::map<std::string, CrateSection>& sections() const { return sections_; }

  // Hostile tests: edits the encoded path tree (path indexes, element
  // tokens, jumps) before it is written.
  std::function<void(std::vector<uint32_t>&, std::vector<int32_t>&, std::vector<int32_t>&)> editPathTree;
  uint64_t tocOffset() const { return tocOffset_; }

 private:
  struct PathNode {
    std::string element;  // the element token ("" for the root)
    bool isProperty = false;
    uint32_t index = 0;
    std::vector<size_t> children;  // into nodes_
  };
  size_t node(const std::string& p);
  void encodeTree(size_t n, std::vector<uint32_t>& indexes, std::vector<int32_t>& tokens,
                  std::vector<int32_t>& jumps);

  uint8_t minor_, patch_;
  std::vector<uint8_t> bytes_;
  std::vector<std::string> tokens_;
  std::map<std::string, uint32_t> tokenIndex_;
  std::vector<uint32_t> strings_;
  std::vector<PathNode> nodes_;
  std::map<std::string, size_t> nodeOf_;
  uint32_t pathCount_ = 0;
  std::vector<uint32_t> fieldTokens_;
  std::vector<uint64_t> fieldReps_;
  std::vector<uint32_t> fieldSets_;
  std::vector<uint32_t> specPaths_, specFieldSets_, specTypes_;
  std::map<std::string, CrateSection> sections_;
  uint64_t tocOffset_ = 0;
};

}  // namespace sdg::usd::test
