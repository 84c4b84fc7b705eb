// `studio`: tune a scene live in the browser (lib/studio).
#include <cstdio>
#include <memory>

#include "commands.h"
#include "studio/studio_server.h"

namespace sdg::cli {

void addStudio(CLI::App& app, int& exitCode) {
  struct Args {
    SceneArgs scene;
    studio::ServerOptions server;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("studio", "Tune a scene live in the browser: its prims, every behavior's exposed "
                                               "variables, a preview per frame, save back into the YAML");
  addSceneArgs(*cmd, args->scene);
  cmd->add_option("--port", args->server.port, "Port to listen on (default: a free one)")
      ->check(CLI::Range(0, 65535))
      ->type_name("N");
  cmd->add_option("--host", args->server.host,
                  "Address to listen on; 127.0.0.1 unless you mean to open the studio to other machines")
      ->capture_default_str()
      ->type_name("ADDR");
  cmd->footer("Prints a URL with an access token; open it in a browser. Ctrl-C stops the server.\n"
              "Example:\n  sdgbehave studio scenes/warehouse.yaml");
  cmd->callback([args, &exitCode] {
    studio::StudioOptions options;
    options.scene = sceneRequest(args->scene);
    studio::serveStudio(options, args->server, [](const std::string& url) {
      std::printf("sdgbehave studio: open %s\n", url.c_str());
      std::fflush(stdout);
    });
    exitCode = kExitOk;
  });
}

}  // namespace sdg::cli
