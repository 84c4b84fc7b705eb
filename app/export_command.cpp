// `sdgbehave export-usd`: the loaded (flattened) stage as a usda layer that
// Isaac Sim opens (scene_io/usd_export.h says what goes where).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "commands.h"
#include "core/diagnostics.h"
#include "core/file_io.h"
#include "scene_io/usd_export.h"
#include "usd/usda_writer.h"

namespace sdg::cli {

void addExportUsd(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<SceneArgs>();
  auto out = std::make_shared<std::string>();
  auto scriptsRoot = std::make_shared<std::string>(kIsaacBehaviorScriptsRoot);
  CLI::App* cmd = app.add_subcommand("export-usd", "Write the flattened stage as a USD layer (.usda) that Isaac Sim "
                                                   "opens: Z-up metres, meshes, lights, cameras, OmniPBR materials, "
                                                   "semantics, behaviors as omni:scripting:scripts");
  addSceneArgs(*cmd, *args);
  cmd->add_option("-o,--out", *out, "The layer to write (.usda)")->required()->type_name("FILE.usda");
  cmd->add_option("--isaac-scripts-root", *scriptsRoot,
                  "Folder of Isaac Sim's behavior scripts: built-in behaviors are written as DIR/location_randomizer.py "
                  "and so on (default: a default Isaac Sim install's)")
      ->type_name("DIR");
  cmd->footer("Run settings, writers and events have no USD home: they go into customLayerData[\"sdgbehave\"].\n"
              "Example:\n  sdgbehave export-usd scenes/warehouse.yaml -o /tmp/warehouse.usda");
  cmd->callback([args, out, scriptsRoot, &exitCode] {
    if (!out->ends_with(".usda"))
      throw SceneError(SourceLoc{"--out", 0, 0}, "expected a file name ending in .usda, found '" + *out + "'");
    LoadedScene loaded = loadSceneForRun(sceneRequest(*args));
    printDropped(loaded);
    UsdExportOptions options;
    options.isaacScriptsRoot = *scriptsRoot;
    while (options.isaacScriptsRoot.size() > 1 && options.isaacScriptsRoot.ends_with('/'))
      options.isaacScriptsRoot.pop_back();
    options.scriptOf = [&loaded](const std::string& behavior) -> std::string {
      const std::string& source = loaded.registry.sourceOf(behavior);
      if (!source.ends_with(".py")) return "";  // a plugin library's behavior
      return std::filesystem::absolute(source).lexically_normal().string();
    };
    options.catalog = &loaded.registry.catalog();
    usd::Layer layer = exportUsdLayer(loaded.scene, loaded.assets, options);
    layer.identifier = *out;
    std::string text;
    try {
      text = usd::writeUsdaLayer(layer);
    } catch (const usd::UsdError& e) {
      throw RunError(std::string("export-usd: ") + e.what());
    }
    writeFileAtomic(*out, text);
    std::printf("%s: %zu prims written to %s\n", args->scene.c_str(), loaded.scene.stage.primCount(), out->c_str());
    exitCode = kExitOk;
  });
}

}  // namespace sdg::cli
