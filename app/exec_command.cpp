#include <memory>

#include "commands.h"
#include "core/log.h"
#include "run/exec_session.h"

namespace sdg::cli {

namespace {
struct ExecArgs {
  std::string program;
  std::vector<std::string> args;
  std::string assetsRoot;
  std::string outRoot;
  unsigned threads = 0;
  int gpu = -1;
  std::string backend;
};
}  // namespace

void addExec(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<ExecArgs>();
  CLI::App* cmd = app.add_subcommand(
      "exec", "Run an Isaac Sim Script Editor program (omni.replicator.core, omni.usd, Isaac's behaviors) unchanged");
  cmd->add_option("program", args->program, "The program (.py)")->required()->type_name("PROGRAM.py");
  cmd->add_option("args", args->args, "Arguments after --, the program's sys.argv[1:]")->type_name("ARGS");
  cmd->add_option("--assets-root", args->assetsRoot,
                  "What get_assets_root_path() answers: a folder holding Isaac/ (Isaac's asset pack). Default: "
                  "$SDGBEHAVE_ASSETS_ROOT, then the stand-in root sdgbehave ships (docs/isaac-scripts.md)")
      ->type_name("DIR");
  cmd->add_option("--out-root", args->outRoot,
                  "The program's working folder (made if missing): where its os.getcwd()-relative output goes. "
                  "Default: the current folder")
      ->type_name("DIR");
  cmd->add_option("--threads", args->threads, "Encoding threads per writer (default: one per core)");
  cmd->add_option("--gpu", args->gpu, "EGL GPU index to render on")->type_name("N");
  cmd->add_option("--backend", args->backend, "GL backend: auto, osmesa or egl")->type_name("NAME");
  cmd->footer(
      "The program runs as in Isaac Sim's Script Editor: its module-level code, then the asyncio tasks it\n"
      "schedules, each `await omni.kit.app.get_app().next_update_async()` one update of sdgbehave's timeline,\n"
      "until every task is done. Exit 0, 1 when the program raises (at its file:line), 2 when it is missing.\n"
      "Example:\n  sdgbehave exec driver.py --out-root /tmp/sdg -- --frames 6");
  cmd->callback([args, &exitCode] {
    ExecOptions options;
    options.program = args->program;
    options.args = args->args;
    options.assetsRoot = args->assetsRoot;
    options.outRoot = args->outRoot;
    options.threads = args->threads;
    options.render.gpu = args->gpu;
    if (!args->backend.empty()) options.render.backend = args->backend;
    ExecResult result = runExec(options);
    log::info(args->program + ": done in " + std::to_string(result.updates) + " update(s), " +
              std::to_string(result.datasets.size()) + " dataset(s)");
    exitCode = kExitOk;
  });
}

}  // namespace sdg::cli
