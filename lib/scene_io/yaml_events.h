#pragma once
// Builds RawNodes straight from yaml-cpp's parse events, without yaml-cpp's
// own node tree. That tree costs ~500 bytes a node, so a 16 MB file of small
// values took 4 GB before any limit could look at it; here the limits are
// checked as each event arrives and memory stays within them.
#include <string>
#include <string_view>

#include "core/source_loc.h"
#include "scene_io/raw_node.h"

namespace sdg {

// Where the document's text starts in its file: --set values are snippets
// of a longer line, so their positions are shifted.
struct TextOrigin {
  FileName file;
  int lineOffset = 0;
  int columnOffset = 0;
};

// Parses the first document of `text`. Syntax errors and every limit in
// raw_node.h throw SceneError with the position where they were found.
RawNode buildRawNodes(std::string_view text, const TextOrigin& origin);

// Parses YAML text. `file` names the source in locations; `lineOffset` and
// `columnOffset` shift them (for snippets such as --set values). Syntax
// errors, alias bombs and too-deep nesting throw SceneError with a location.
RawNode parseYaml(std::string_view text, const std::string& file, int lineOffset = 0, int columnOffset = 0);
// Reads and parses a file; a missing, unreadable or oversized file throws SceneError.
RawNode parseYamlFile(const std::string& path);

}  // namespace sdg
