#include "scene_io/raw_node.h"

#include <fstream>
#include <sstream>
#include <sys/stat.h>

#include "core/diagnostics.h"
#include "core/text.h"
#include "scene_io/yaml_events.h"

namespace sdg {

RawNode::RawNode() = default;
RawNode::~RawNode() = default;
RawNode::RawNode(const RawNode&) = default;
RawNode::RawNode(RawNode&&) noexcept = default;
RawNode& RawNode::operator=(const RawNode&) = default;
RawNode& RawNode::operator=(RawNode&&) noexcept = default;

const RawNode* RawNode::find(std::string_view key) const {
  for (const auto& [k, v] : entries)
    if (k.isScalar() && k.scalar == key) return &v;
  return nullptr;
}

std::string RawNode::describe() const {
  switch (kind) {
    case Kind::Null: return "nothing (null)";
    case Kind::Map: return "a mapping";
    case Kind::Sequence:
      return "a list of " + std::to_string(items.size()) + (items.size() == 1 ? " item" : " items");
    case Kind::Scalar: return (quoted ? "the string " : "") + text::quote(scalar);
  }
  return {};
}

RawNode parseYaml(std::string_view text, const std::string& file, int lineOffset, int columnOffset) {
  return buildRawNodes(text, TextOrigin{file, lineOffset, columnOffset});
}

RawNode parseYamlFile(const std::string& path) {
  SourceLoc fileLoc{path, 0, 0};
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) throw SceneError(fileLoc, "cannot open the scene file: it does not exist");
  if (S_ISDIR(info.st_mode)) throw SceneError(fileLoc, "cannot open the scene file: it is a directory");
  if (static_cast<size_t>(info.st_size) > kMaxSceneFileBytes)
    throw SceneError(fileLoc, "the scene file is " + std::to_string(info.st_size) +
                                  " bytes; scene files are limited to " + std::to_string(kMaxSceneFileBytes) +
                                  " bytes (keep bulk data in asset files)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(fileLoc, "cannot open the scene file: permission denied or unreadable");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parseYaml(buffer.str(), path);
}

}  // namespace sdg
