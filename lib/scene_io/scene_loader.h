#pragma once
// YAML scene -> Scene, in passes: parse to located raw nodes; read settings;
// declare prims (paths, types, parents); fill each prim (attributes, xform
// ops, labels, material, behaviors with their exposed variables); apply the
// --set overrides; check cross references. Every problem of the file is
// collected and reported together as one SceneError.
#include <span>
#include <string>
#include <vector>

#include "scene_io/raw_node.h"
#include "scene_io/scene.h"
#include "stage/behavior_spec.h"

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

class AssetLibrary;

// Builds the scene; throws SceneError listing every problem. Prims with
// `reference:` are mounted from `assets` (a library of this load; one is
// made for the call when null).
Scene buildScene(const SceneDocument& doc, const BehaviorCatalog& catalog,
                 std::span<const std::string> overrides = {}, AssetLibrary* assets = nullptr);

Scene loadScene(const std::string& path, const BehaviorCatalog& catalog,
                std::span<const std::string> overrides = {});

}  // namespace sdg
