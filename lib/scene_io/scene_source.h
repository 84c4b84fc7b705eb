#pragma once
// The one way in for a scene file, whatever it is: a YAML scene (with the
// smart assets and USD files it mounts) or a USD stage run on its own
// (.usd, .usda, .usdc, .usdz). Both give a validated Scene with the
// --set overrides applied, every file the scene was read from, and what
// its USD content does not carry over.
//
// Behavior scripts and plugins are the program's business, not this
// library's: what a file a scene names stands for is decided by the
// SceneScriptHost the caller gives (run/ implements it with its behavior
// registry and the embedded interpreter), so scene_io never guesses a
// script's behaviors from its text.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/dropped.h"
#include "core/source_loc.h"
#include "scene_io/attached_scripts.h"
#include "scene_io/scene.h"
#include "stage/behavior_spec.h"

namespace sdg {

struct SceneSource {
  std::string path;
  // The scene's text when it is not read from `path` (the studio's edits
  // not saved yet; YAML only); locations still name `path`.
  std::optional<std::string> text;
  std::vector<std::string> overrides;  // --set
  // Smart-asset files' texts that replace theirs on disk (keys: assetKey()).
  std::map<std::string, std::string> assetTexts;
};

// What reading a scene needs from the program that runs it.
class SceneScriptHost {
 public:
  virtual ~SceneScriptHost() = default;
  // The behaviors known so far: prims are read against it, and it grows as
  // the calls below load scripts and plugins.
  virtual const BehaviorCatalog& catalog() const = 0;
  // A behavior script a scene's (or a smart asset's) `scripts:` names
  // (absolute, existing); SceneError at `where` when it does not load.
  virtual void loadScript(const std::string& path, const SourceLoc& where) = 0;
  // A plugin library a scene's `plugins:` names (absolute, existing).
  virtual void loadPlugin(const std::string& path, const SourceLoc& where) = 0;
  // The scene's own run.isaac_scripts, said before the first attach (nullopt:
  // the scene does not say; a USD stage never does).
  virtual void sceneIsaacScripts(std::optional<IsaacScriptChoice> setting) = 0;
  // The behaviors a file listed in omni:scripting:scripts stands for
  // (loading it when it is a script); SceneError at `where` when it cannot.
  virtual std::vector<std::string> attach(const std::string& path, const SourceLoc& where) = 0;
};

struct SceneSourceRead {
  Scene scene;
  // The `scripts:` and `plugins:` files the scene and its smart assets
  // declared (absolute, in load order), loaded through the host.
  std::vector<std::string> scriptFiles, pluginFiles;
  // Every file the scene mounts: smart-asset files, USD layers and packages
  // (absolute, normalized, each once).
  std::vector<std::string> mountedFiles;
  // One warning per kind of USD content not carried over (usd_losses.h).
  std::vector<DroppedWarning> dropped;
};

// A USD stage file by its extension (any case).
bool isUsdStagePath(const std::string& path);

// Reads, builds and validates the scene; SceneError (exit 2) listing every
// problem, located.
SceneSourceRead readSceneSource(const SceneSource& source, SceneScriptHost& host);

}  // namespace sdg
