#include "run/scene_setup.h"

#include <filesystem>

#include "behaviors/builtin_behaviors.h"
#include "scene_io/scene_loader.h"

namespace sdg {

BehaviorRegistry registryWithPlugins(const std::vector<std::string>& plugins) {
  BehaviorRegistry registry = builtinRegistry();
  for (size_t i = 0; i < plugins.size(); ++i)
    registry.loadPlugin(plugins[i], SourceLoc{"--plugin[" + std::to_string(i + 1) + "]", 0, 0});
  return registry;
}

RenderSettings renderSettingsFor(const Scene& scene, std::optional<int> width, std::optional<int> height,
                                 std::optional<int> subframes) {
  RenderSettings settings;
  const Vec2i resolution = scene.render.get("resolution").get<Vec2i>();
  settings.width = width.value_or(resolution.x());
  settings.height = height.value_or(resolution.y());
  settings.subframes = subframes.value_or(int(scene.render.getUInt("subframes")));
  return settings;
}

LoadedScene loadSceneForRun(const SceneRequest& request) {
  SceneDocument doc = readSceneDocument(request.scenePath);
  BehaviorRegistry registry = registryWithPlugins(request.plugins);
  // The scene's own plugins load before its prims are read: their behaviors
  // must be known to check the prims. Paths are relative to the scene file.
  std::filesystem::path sceneDir = std::filesystem::path(request.scenePath).parent_path();
  for (const std::string& plugin : declaredPlugins(doc)) {
    std::filesystem::path p(plugin);
    if (p.is_relative()) p = sceneDir / p;
    registry.loadPlugin(p.string(), SourceLoc{request.scenePath, 0, 0});
  }
  Scene scene = buildScene(doc, registry.catalog(), request.overrides);
  AssetResolver assets = makeSceneResolver(scene.sourceDir, scene.assetRoots, request.assetRoots);
  return LoadedScene{std::move(registry), std::move(scene), std::move(assets)};
}

}  // namespace sdg
