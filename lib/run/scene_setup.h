#pragma once
// Everything a command needs before it can work with a scene: the behavior
// registry (built-ins, --plugin libraries, the scene's plugins:), the loaded
// and validated scene, and its asset resolver.
#include <string>
#include <vector>

#include <map>
#include <optional>

#include "assets/asset_resolver.h"
#include "core/dropped.h"
#include "render/raster/renderer.h"
#include "behavior/registry.h"
#include "behavior/behavior.h"
#include "physics/physics_settings.h"
#include "scene_io/scene.h"
#include "scene_io/scene_source.h"  // isUsdStagePath, for the callers that branch on it

namespace sdg {

struct SceneRequest {
  std::string scenePath = {};
  std::vector<std::string> overrides = {};   // --set
  std::vector<std::string> plugins = {};     // --plugin
  std::vector<std::string> scripts = {};     // --script
  std::vector<std::string> assetRoots = {};  // --asset-root
  std::string isaacAssets = {};              // --isaac-assets ("" = SDGBEHAVE_ISAAC_ASSETS, then the scene's)
  std::optional<double> hookTimeout = {};    // --hook-timeout (unset: the scene's run.hook_timeout)
  std::string isaacScripts = {};             // --isaac-scripts auto|builtin|script ("": run.isaac_scripts)
  // The scene's text when it is not read from scenePath (the studio's edits
  // not saved yet); locations still name scenePath.
  std::optional<std::string> sceneText = {};
  // Smart-asset files' texts that replace theirs on disk (keys: assetKey()).
  std::map<std::string, std::string> assetTexts = {};
  // Resolve asset files only inside the asset roots (the studio: a value
  // typed in a page opens no file elsewhere; AssetResolver::confineToRoots).
  bool confineAssets = false;
};

struct LoadedScene {
  BehaviorRegistry registry;
  Scene scene;
  AssetResolver assets;
  // Every behavior script the scene loaded, its referenced assets' too
  // (absolute, in load order, each once per listing).
  std::vector<std::string> scriptFiles;
  // Every smart-asset file the scene mounts, and every plugin library it
  // loaded (absolute): with the above, what the run's identity hashes.
  std::vector<std::string> mountedFiles;
  std::vector<std::string> pluginFiles;
  // What the scene's USD files have that the stage does not carry over: one
  // warning per kind of loss (scene_io/usd_losses.h), for the commands to
  // print; `validate --strict` fails on them.
  std::vector<DroppedWarning> dropped;
};

// Command-line overrides of the scene's render section (--resolution,
// --subframes, --backend, --gpu), shared by `run` and `render`.
struct RenderOverrides {
  std::optional<int> width, height, subframes;
  std::optional<std::string> mode;  // raster | pathtraced
  std::optional<int> samples;
  std::optional<bool> denoise;
  std::optional<std::string> backend;  // auto | osmesa | egl
  int gpu = -1;                        // EGL GPU index; -1: the first
};
// The scene's render settings with the overrides applied.
RenderSettings renderSettingsFor(const Scene& scene, const RenderOverrides& overrides);
// What a scene that says nothing of rendering gets: the render option
// table's defaults (scene_io/settings_specs.cpp), the only place they are written.
RenderSettings defaultRenderSettings();
// The GL context for a run or a picture (RunError naming what was tried).
std::unique_ptr<GlContext> glContextFor(const Scene& scene, const RenderOverrides& overrides);

// The scene's physics section as the settings the stacking code reads.
PhysicsSettings physicsSettingsFor(const Scene& scene);

// What the run's behaviors may use: the scene's assets and physics
// settings, and a report hook that appends to `reports` (settle quality).
struct RunBehaviorSetup {
  PhysicsSettings physics;
  std::vector<nlohmann::ordered_json> reports;
};
BehaviorContext behaviorContextFor(LoadedScene& loaded, int64_t seed, RunBehaviorSetup& setup);

// The scene as one self-contained file (`sdgbehave flatten`): references
// expanded (the loaded stage is flat), asset roots, scripts (the assets'
// too) and plugins absolute, so it reloads from any folder to the same stage.
Scene flattenedScene(const LoadedScene& loaded);

// `--save-stage FILE`: the scene as it stands after the pre-roll, without
// its events (they have run), so reloading it renders the same stacks.
void saveStageAfterPreroll(const LoadedScene& loaded, const std::string& path);

// Loads and checks the scene (scene_io/scene_source.h: a YAML scene or a USD
// stage, scripts and plugins loaded through the run's registry), including
// that every file it names (meshes, textures, behaviors' file lists,
// plugins) exists and can be read, and sets
// the time limit of calls into behavior scripts (--hook-timeout, else
// run.hook_timeout). Throws SceneError for invalid input (exit 2).
LoadedScene loadSceneForRun(const SceneRequest& request);
// Runs a behavior script again after it changed on disk, so that scenes
// loaded from now on get its new classes (scripting::reloadScript: a
// SceneError says why a script no longer loads; the last good one stays).
void reloadBehaviorScript(const std::string& path);
// The registry of built-ins plus the given plugin libraries and behavior
// scripts (--plugin / --script; problems located at the flag).
BehaviorRegistry registryWithPlugins(const std::vector<std::string>& plugins,
                                     const std::vector<std::string>& scripts = {});

}  // namespace sdg
