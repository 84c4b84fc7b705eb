#pragma once
// A YAML document as plain nodes that carry their source location. yaml-cpp
// is used only to build these; no yaml-cpp type leaves scene_io.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/source_loc.h"

namespace sdg {

struct RawEntry;

struct RawNode {
  enum class Kind { Null, Scalar, Sequence, Map };

  // Out of line: RawEntry holds RawNodes, so it is complete only below.
  RawNode();
  ~RawNode();
  RawNode(const RawNode&);
  RawNode(RawNode&&) noexcept;
  RawNode& operator=(const RawNode&);
  RawNode& operator=(RawNode&&) noexcept;

  Kind kind = Kind::Null;
  std::string scalar;   // Scalar text
  bool quoted = false;  // Scalar written in quotes (so never a number or bool)
  SourceLoc loc;
  std::vector<RawNode> items;                          // Sequence
  std::vector<RawEntry> entries;                       // Map, document order

  bool isNull() const { return kind == Kind::Null; }
  bool isScalar() const { return kind == Kind::Scalar; }
  bool isSequence() const { return kind == Kind::Sequence; }
  bool isMap() const { return kind == Kind::Map; }
  // The value under `key` in a map, or nullptr.
  const RawNode* find(std::string_view key) const;
  // For messages: "a mapping", "a list of 2 items", "the string 'abc'", ...
  std::string describe() const;
};

struct RawEntry {
  RawNode key;
  RawNode value;
};

// Documented limits that keep hostile documents bounded in memory and time.
inline constexpr size_t kMaxSceneFileBytes = 64u << 20;   // 64 MiB
inline constexpr size_t kMaxDocumentNodes = 2'000'000;    // after alias expansion
inline constexpr int kMaxDocumentDepth = 1000;             // nesting levels, counted through aliases
inline constexpr size_t kMaxDocumentTextBytes = kMaxSceneFileBytes;  // scalar text, after alias expansion

}  // namespace sdg
