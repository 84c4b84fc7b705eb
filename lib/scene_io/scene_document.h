#pragma once
// A scene file read into located raw nodes, before any of it is
// interpreted, and the lenient look at the files it declares (plugins,
// scripts) that must load before its prims can be checked.
#include <string>
#include <string_view>
#include <vector>

#include "core/source_loc.h"
#include "scene_io/raw_node.h"

namespace sdg {

struct SceneDocument {
  std::string path;
  RawNode root;
};

// Reads and parses the file (syntax errors throw SceneError).
SceneDocument readSceneDocument(const std::string& path);
SceneDocument sceneDocumentFromText(std::string_view yaml, const std::string& name);

// The `plugins:` or `scripts:` the document declares, read leniently (the full check
// happens in buildScene): plugins must load before behaviors are checked.
struct DeclaredFile {
  std::string path;  // as written, relative to the scene file
  SourceLoc loc;
};
// `key` is "plugins" or "scripts".
std::vector<DeclaredFile> declaredFiles(const SceneDocument& doc, std::string_view key);

}  // namespace sdg
