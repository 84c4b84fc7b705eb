#include <cstdio>
#include <memory>


#include "commands.h"
#include "core/diagnostics.h"
#include "core/log.h"
#include "run/quick_render.h"

namespace sdg::cli {

namespace {
struct RenderArgs {
  BackendArgs backend;
  SceneArgs scene;
  std::string camera;
  std::string out;
  std::string resolution;
  std::optional<int> subframes;
};

}  // namespace

void addRender(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render one picture of a scene as authored (a quick look)");
  addSceneArgs(*cmd, args->scene);
  addBackendArgs(*cmd, args->backend);
  cmd->add_option("--camera", args->camera, "Camera prim (default: the first of capture.cameras)")->type_name("PATH");
  cmd->add_option("-o,--out", args->out, "PNG file to write")->required()->type_name("FILE.png");
  cmd->add_option("--resolution", args->resolution, "Image size, e.g. 640x480 (overrides render.resolution)")
      ->type_name("WxH");
  cmd->add_option("--subframes", args->subframes, "Anti-aliasing samples (overrides render.subframes)")
      ->check(CLI::Range(1, 64))
      ->type_name("K");
  cmd->footer("Example:\n  sdgbehave render scenes/warehouse.yaml --out warehouse.png --resolution 640x480");
  cmd->callback([args, &exitCode] {
    QuickRenderOptions options;
    options.camera = args->camera;
    options.outputPath = args->out;
    options.subframes = args->subframes;
    if (!args->backend.backend.empty()) options.backend.backend = args->backend.backend;
    options.backend.gpu = args->backend.gpu;
    if (!args->resolution.empty()) {
      auto [w, h] = parseResolution(args->resolution);
      options.width = w;
      options.height = h;
    }
    LoadedScene loaded = loadSceneForRun(
        SceneRequest{args->scene.scene, args->scene.overrides, args->scene.plugins, args->scene.assetRoots});
    QuickRenderResult result = renderOnePicture(loaded, options);
    log::info("wrote " + args->out + " (" + std::to_string(result.width) + " x " + std::to_string(result.height) +
              ", camera " + result.camera + ", " + result.renderer + ")");
    exitCode = kExitOk;
  });
}

}  // namespace sdg::cli
