#pragma once
// Reads the keys of one YAML mapping and refuses what it did not use: every
// key not asked for is reported as unknown, with a "did you mean".
#include <string>
#include <string_view>
#include <vector>

#include "core/diagnostics.h"
#include "scene_io/raw_node.h"

namespace sdg {

class MapReader {
 public:
  // Reports (and marks !ok()) when `node` is not a mapping or repeats a key.
  MapReader(const RawNode& node, std::string what, Diagnostics& diag);

  bool ok() const { return ok_; }
  const std::string& what() const { return what_; }
  // The value under `key`, or nullptr; either way `key` becomes known.
  const RawNode* get(std::string_view key);
  // Like get, but a missing key is an error.
  const RawNode* require(std::string_view key);
  // Marks a key as known without reading it (read elsewhere).
  void allow(std::string_view key) { known_.emplace_back(key); }
  // Reports every key that was neither read nor allowed.
  void finish();

 private:
  const RawNode& node_;
  std::string what_;
  Diagnostics& diag_;
  bool ok_ = true;
  std::vector<std::string> known_;
};

// "what.key" for nested messages ("render.resolution").
std::string joinWhat(std::string_view what, std::string_view key);
// Reports duplicate keys of a mapping; true when there were none.
bool checkUniqueKeys(const RawNode& map, std::string_view what, Diagnostics& diag);

}  // namespace sdg
