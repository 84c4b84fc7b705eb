#pragma once
// Everything a command needs before it can work with a scene: the behavior
// registry (built-ins, --plugin libraries, the scene's plugins:), the loaded
// and validated scene, and its asset resolver.
#include <string>
#include <vector>

#include <optional>

#include "assets/asset_resolver.h"
#include "render/renderer.h"
#include "behavior/registry.h"
#include "scene_io/scene.h"

namespace sdg {

struct SceneRequest {
  std::string scenePath;
  std::vector<std::string> overrides;   // --set
  std::vector<std::string> plugins;     // --plugin
  std::vector<std::string> assetRoots;  // --asset-root
};

struct LoadedScene {
  BehaviorRegistry registry;
  Scene scene;
  AssetResolver assets;
};

// The scene's render settings with command-line overrides applied.
RenderSettings renderSettingsFor(const Scene& scene, std::optional<int> width, std::optional<int> height,
                                 std::optional<int> subframes);

// Throws SceneError for invalid input (exit 2).
LoadedScene loadSceneForRun(const SceneRequest& request);
// The registry of built-ins plus the given plugin libraries.
BehaviorRegistry registryWithPlugins(const std::vector<std::string>& plugins);

}  // namespace sdg
