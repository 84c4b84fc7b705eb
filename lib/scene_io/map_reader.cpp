#include "scene_io/map_reader.h"

#include <algorithm>
#include <unordered_map>

#include "core/text.h"

namespace sdg {

std::string joinWhat(std::string_view what, std::string_view key) {
  if (what.empty()) return std::string(key);
  return std::string(what) + "." + std::string(key);
}

bool checkUniqueKeys(const RawNode& map, std::string_view what, Diagnostics& diag) {
  bool unique = true;
  std::unordered_map<std::string_view, const RawNode*> seen;
  for (const auto& [key, value] : map.entries) {
    if (!key.isScalar()) {
      diag.error(key.loc, std::string(what) + ": keys must be plain strings, found " + key.describe());
      unique = false;
      continue;
    }
    auto [it, inserted] = seen.emplace(key.scalar, &key);
    if (!inserted) {
      diag.error(key.loc, std::string(what) + ": duplicate key " + text::quote(key.scalar) + " (first at line " +
                              std::to_string(it->second->loc.line) + ")");
      unique = false;
    }
  }
  return unique;
}

MapReader::MapReader(const RawNode& node, std::string what, Diagnostics& diag)
    : node_(node), what_(std::move(what)), diag_(diag) {
  if (node.isNull()) return;  // an empty section: every key takes its default
  if (!node.isMap()) {
    diag_.error(node.loc, (what_.empty() ? std::string("the scene") : what_) + ": expected a mapping, found " +
                              node.describe());
    ok_ = false;
    return;
  }
  ok_ = checkUniqueKeys(node, what_.empty() ? "the scene" : what_, diag);
}

const RawNode* MapReader::get(std::string_view key) {
  known_.emplace_back(key);
  if (!node_.isMap()) return nullptr;
  return node_.find(key);
}

const RawNode* MapReader::require(std::string_view key) {
  const RawNode* value = get(key);
  if (!value && ok_)
    diag_.error(node_.loc, (what_.empty() ? std::string("the scene") : what_) + ": missing required key " +
                               text::quote(key));
  return value;
}

void MapReader::finish() {
  if (!node_.isMap()) return;
  for (const auto& [key, value] : node_.entries) {
    if (!key.isScalar()) continue;  // reported by checkUniqueKeys
    if (std::find(known_.begin(), known_.end(), key.scalar) != known_.end()) continue;
    diag_.error(key.loc, (what_.empty() ? std::string("the scene") : what_) + ": unknown key " +
                             text::quote(key.scalar) + text::didYouMean(key.scalar, known_));
  }
}

}  // namespace sdg
