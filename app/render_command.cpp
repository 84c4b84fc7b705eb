#include <cstdio>
#include <memory>


#include "commands.h"
#include "core/diagnostics.h"
#include "core/log.h"
#include "run/quick_render.h"

namespace sdg::cli {

namespace {
struct RenderArgs {
  SceneArgs scene;
  ImageArgs image;
  std::string camera;
  std::string out;
};

}  // namespace

void addRender(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render one picture of a scene as authored (a quick look)");
  addSceneArgs(*cmd, args->scene);
  cmd->add_option("--camera", args->camera, "Camera prim (default: the first of capture.cameras)")->type_name("PATH");
  cmd->add_option("-o,--out", args->out, "PNG file to write")->required()->type_name("FILE.png");
  addImageArgs(*cmd, args->image);
  cmd->footer("Example:\n  sdgbehave render scenes/warehouse.yaml --out warehouse.png --resolution 640x480");
  cmd->callback([args, &exitCode] {
    QuickRenderOptions options;
    options.camera = args->camera;
    options.outputPath = args->out;
    options.render = renderOverrides(args->image);
    LoadedScene loaded = loadSceneForRun(sceneRequest(args->scene));
    printDropped(loaded);
    QuickRenderResult result = renderOnePicture(loaded, options);
    log::info("wrote " + args->out + " (" + std::to_string(result.width) + " x " + std::to_string(result.height) +
              ", camera " + result.camera + ", " + result.renderer + ")");
    exitCode = kExitOk;
  });
}

}  // namespace sdg::cli
