#include <cstdio>
#include <memory>
#include <optional>

#include "commands.h"
#include "core/diagnostics.h"
#include "core/log.h"
#include "run/timeline_run.h"

namespace sdg::cli {

namespace {
struct RunArgs {
  SceneArgs scene;
  std::optional<uint64_t> frames;
  std::optional<int64_t> seed;
  bool noRender = false;
  std::string record;
};
}  // namespace

void addRun(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand("run", "Run a scene: pre-roll events, then play the timeline frame by frame");
  addSceneArgs(*cmd, args->scene);
  cmd->add_option("--frames", args->frames, "Frames to capture (overrides capture.frames)")->type_name("N");
  cmd->add_option("--seed", args->seed, "Run seed (overrides capture.seed)")->type_name("S");
  cmd->add_flag("--no-render", args->noRender, "Step behaviors only; write no images (use with --record)");
  cmd->add_option("--record", args->record,
                  "Write every attribute behaviors change, per frame, as JSON lines (prim, attribute, value)")
      ->type_name("FILE.jsonl");
  cmd->footer(
      "Example:\n"
      "  sdgbehave run scenes/examples/location_randomizer.yaml --frames 6 --seed 10 --no-render --record changes.jsonl");
  cmd->callback([args, &exitCode] {
    if (!args->noRender)
      throw SceneError(SourceLoc{"run", 0, 0},
                       "rendering is not available in this build yet; run with --no-render (and --record FILE) "
                       "to step the behaviors");
    LoadedScene loaded = loadSceneForRun(SceneRequest{args->scene.scene, args->scene.overrides,
                                                      args->scene.plugins, args->scene.assetRoots});
    TimelineRunOptions options;
    options.frames = args->frames.value_or(loaded.scene.capture.getUInt("frames"));
    options.seed = args->seed.value_or(loaded.scene.capture.getInt("seed"));
    options.recordPath = args->record;
    TimelineRunResult result = runTimeline(loaded, options);
    log::info(args->scene.scene + ": " + std::to_string(result.frames) + " frames, " +
              std::to_string(result.behaviors) + " behaviors, " + std::to_string(result.updates) + " updates" +
              (args->record.empty() ? "" : "; changes recorded in " + args->record));
    exitCode = kExitOk;
  });
}

}  // namespace sdg::cli
