#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "commands.h"
#include "core/diagnostics.h"
#include "core/log.h"
#include "core/file_io.h"
#include "core/text.h"
#include "run/dataset_run.h"
#include "run/frame_plan.h"
#include "run/gpu_workers.h"
#include "run/output_folder.h"
#include "run/progress.h"
#include "run/run_summary.h"
#include "run/timeline_run.h"

namespace sdg::cli {

namespace {
struct RunArgs {
  SceneArgs scene;
  std::optional<uint64_t> frames;
  std::optional<int64_t> seed;
  bool noRender = false;
  std::string record;
  std::string out;
  bool overwrite = false;
  unsigned threads = 0;
  ImageArgs image;
  std::string summary;
  std::string saveStage;
  std::optional<uint64_t> iterations;
  std::string shard;
  std::optional<uint64_t> shardIndex, shardCount;
  bool resume = false;
  std::vector<std::string> cameras;
  std::string gpus;
};

// The command line for a worker of --gpus: this run's arguments without
// --gpus (the workers get --gpu, --shard and --threads of their own).
std::vector<std::string> workerArguments() {
  std::vector<std::string> out;
  const std::vector<std::string>& all = commandLine();
  for (size_t i = 0; i < all.size(); ++i) {
    if (all[i] == "--gpus" || all[i] == "--threads") {
      ++i;  // and its value
      continue;
    }
    if (all[i].starts_with("--gpus=") || all[i].starts_with("--threads=")) continue;
    out.push_back(all[i]);
  }
  return out;
}

// `run --gpus`: true when it ran the workers (two or more GPUs); with one
// GPU the run goes on as today on that GPU, with none as today.
bool runOnSeveralGpus(const RunArgs& args, LoadedScene& loaded, ImageArgs& image) {
  const SourceLoc flag{"--gpus", 0, 0};
  if (args.noRender) throw SceneError(flag, "--gpus renders frames; --no-render takes none");
  if (!args.shard.empty() || args.shardIndex || args.shardCount)
    throw SceneError(flag, "--gpus splits the run into one shard per GPU itself; it takes no --shard");
  if (image.gpu >= 0) throw SceneError(flag, "give --gpus or --gpu, not both");
  const std::vector<int> gpus = gpusFromSpec(args.gpus);
  if (gpus.size() == 1) image.gpu = gpus.front();
  if (gpus.size() < 2) return false;
  if (args.overwrite)
    throw SceneError(flag, "--gpus writes one shard per GPU into the folder, which --overwrite would let one worker "
                           "empty under another; use an empty folder, or --resume");
  if (!args.record.empty() || !args.saveStage.empty() || !args.summary.empty())
    throw SceneError(flag, "--record, --save-stage and --summary are for one process; run without --gpus");
  const FramePlan plan = framePlanFor(loaded.scene, FramePlanFlags{args.frames, args.iterations, "", {}, {}},
                                      processEnvironment);
  GpuWorkersOptions options;
  options.executable = std::filesystem::read_symlink("/proc/self/exe").string();
  options.args = workerArguments();
  options.gpus = gpus;
  options.threads = args.threads;
  options.outDir = args.out.empty() ? "out/" + std::filesystem::path(args.scene.scene).stem().string() : args.out;
  options.totalFrames = plan.iterations * plan.framesPerIteration;
  options.progress = Progress::stderrIsTerminal() && log::enabled(log::Level::Info);
  const GpuWorkersResult result = runOnGpus(options);
  char line[320];
  std::snprintf(line, sizeof line, "%llu frames, %llu files in %s on %zu GPUs: %.2f s, %.1f frames/s",
                static_cast<unsigned long long>(result.frames), static_cast<unsigned long long>(result.files),
                options.outDir.c_str(), gpus.size(), result.seconds,
                result.seconds > 0 ? double(result.frames) / result.seconds : 0.0);
  log::info(line);
  return true;
}

// --camera: the render products (capture.cameras), each a Camera prim of
// the stage; anything else is bad usage naming the flag.
void selectCameras(LoadedScene& loaded, const std::vector<std::string>& cameras) {
  if (cameras.empty()) return;
  std::vector<std::string> names;
  loaded.scene.stage.traverse([&](const Prim& p) {
    if (p.type() == PrimType::Camera) names.push_back(p.path());
  });
  for (const std::string& camera : cameras)
    if (std::find(names.begin(), names.end(), camera) == names.end())
      throw SceneError(SourceLoc{"--camera", 0, 0},
                       text::quote(camera) + " is not a Camera of the scene; cameras: " +
                           (names.empty() ? std::string("none") : text::join(names, ", ")) + text::didYouMean(camera, names));
  loaded.scene.capture.set("cameras", Value::makeStringArray(cameras));
}

// What the flags ask of the frame plan (run/frame_plan.h decides it).
FramePlanFlags framePlanFlags(const RunArgs& args) {
  return FramePlanFlags{args.frames, args.iterations, args.shard, args.shardIndex, args.shardCount};
}
}  // namespace

void addRun(CLI::App& app, int& exitCode) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand("run", "Run a scene: pre-roll events, then play the timeline frame by frame");
  addSceneArgs(*cmd, args->scene);
  addHookTimeoutArg(*cmd, args->scene);
  cmd->add_option("--frames", args->frames, "Frames to capture (overrides capture.frames)")->type_name("N");
  cmd->add_option("--seed", args->seed, "Run seed (overrides capture.seed)")->type_name("S");
  cmd->add_option("-o,--out", args->out, "Output folder (default: out/<scene name>)")->type_name("DIR");
  cmd->add_flag("--overwrite", args->overwrite, "Write into a non-empty output folder, replacing its files");
  cmd->add_option("--threads", args->threads, "Encoding and writing threads (default: one per core)")
      ->check(CLI::Range(1u, 256u))
      ->type_name("N");
  addImageArgs(*cmd, args->image);
  cmd->add_option("--summary", args->summary, "Also write the run summary (JSON) to this file")
      ->type_name("FILE.json");
  cmd->add_flag("--no-render", args->noRender, "Step behaviors only; write no images (use with --record)");
  cmd->add_option("--record", args->record,
                  "Write every attribute behaviors change, per frame, as JSON lines (prim, attribute, value)")
      ->type_name("FILE.jsonl");
  cmd->add_option("--save-stage", args->saveStage,
                  "After the pre-roll, write the scene with its stacks in place (and no events) to this file: "
                  "stack once, render many times")
      ->type_name("FILE.yaml");
  cmd->add_option("--iterations", args->iterations,
                  "Repetitions of pre-roll + frames, each with fresh random streams (overrides capture.iterations)")
      ->check(CLI::Range(uint64_t(1), uint64_t(1) << 40))
      ->type_name("I");
  cmd->add_option("--shard", args->shard,
                  "Render only shard i of k (0-based; a contiguous block of frames) into the shared --out; "
                  "defaults from Slurm array or Kubernetes Indexed Job variables")
      ->type_name("i/k");
  cmd->add_option("--shard-index", args->shardIndex, "Same as the i of --shard")->type_name("i");
  cmd->add_option("--shard-count", args->shardCount, "Same as the k of --shard")->type_name("k");
  cmd->add_option("--camera", args->cameras,
                  "Render from this Camera prim (repeat for several; overrides capture.cameras)")
      ->type_name("PATH")
      ->allow_extra_args(false);
  cmd->add_option("--gpus", args->gpus,
                  "Use several GPUs of this machine: all, a number (the first N) or a list (0,2,3); one worker "
                  "process per GPU renders a shard with its share of the cores, then the shards are merged into the "
                  "dataset one process writes. One GPU or none: as without it")
      ->type_name("all|N|LIST");
  cmd->add_flag("--resume", args->resume,
                "Continue an interrupted run in --out: keep frames the manifest lists with matching files, redo the rest");
  cmd->footer(
      "Example:\n"
      "  sdgbehave run scenes/warehouse.yaml --frames 6 --seed 10 --out out/warehouse\n"
      "  sdgbehave run scenes/examples/location_randomizer.yaml --frames 6 --seed 10 --no-render --record changes.jsonl\n"
      "  sdgbehave run scenes/warehouse.yaml --iterations 4 --frames 25 --shard 1/4 --out /shared/ds   # then: merge\n"
      "  sdgbehave run scenes/warehouse.yaml --frames 600 --out out/big --resume   # after a crash");
  cmd->callback([args, &exitCode] {
    const auto loadStart = std::chrono::steady_clock::now();
    LoadedScene loaded = loadSceneForRun(sceneRequest(args->scene));
    printDropped(loaded);
    selectCameras(loaded, args->cameras);
    if (!args->gpus.empty() && runOnSeveralGpus(*args, loaded, args->image)) {
      exitCode = kExitOk;
      return;
    }
    const double loadSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - loadStart).count();
    if (!args->noRender) {
      DatasetRunOptions options;
      options.plan = framePlanFor(loaded.scene, framePlanFlags(*args), processEnvironment);
      options.resume = args->resume;
      options.seed = args->seed.value_or(loaded.scene.capture.getInt("seed"));
      options.outDir = args->out.empty() ? "out/" + std::filesystem::path(args->scene.scene).stem().string() : args->out;
      options.overwrite = args->overwrite;
      options.threads = args->threads;
      options.recordPath = args->record;
      options.saveStagePath = args->saveStage;
      options.render = renderOverrides(args->image);
      options.progress = Progress::stderrIsTerminal() && log::enabled(log::Level::Info);
      DatasetRunResult result = runDataset(loaded, options);
      const nlohmann::ordered_json summaryJson =
          makeRunSummary(RunSummaryInputs{versionText(), args->scene.scene, &loaded.scene, &options, &result, loadSeconds,
                                          &loaded.dropped});
      std::string summary = summaryJson.dump(2) + "\n";
      // A shard's summary waits beside the others for `sdgbehave merge`.
      const std::filesystem::path summaryPath =
          options.plan.shard.sharded()
              ? std::filesystem::path(options.outDir) / kPartsFolder / ("summary." + options.plan.shard.tag() + ".json")
              : std::filesystem::path(options.outDir) / "run_summary.json";
      writeFileAtomic(summaryPath.string(), summary);
      if (!args->summary.empty()) writeFileAtomic(args->summary, summary);
      char line[320];
      std::snprintf(line, sizeof line, "%llu frames%s, %llu files in %s: %.2f s, %.1f frames/s, peak %.0f MB (%s, %s)",
                    static_cast<unsigned long long>(result.frames),
                    result.resumedFrames ? (" (" + std::to_string(result.resumedFrames) + " kept from before)").c_str() : "",
                    summaryJson["files_written"].get<unsigned long long>(), options.outDir.c_str(),
                    loadSeconds + result.seconds, result.seconds > 0 ? double(result.frames) / result.seconds : 0.0,
                    peakRssMb(), result.backend.c_str(), result.device.c_str());
      log::info(line);
      if (options.plan.shard.sharded())
        log::info("shard " + std::to_string(options.plan.shard.index) + " of " + std::to_string(options.plan.shard.count) +
                  " done (frames " + std::to_string(options.plan.ownedBegin()) + " to " +
                  std::to_string(options.plan.ownedEnd()) + "); when every shard is done: sdgbehave merge " +
                  options.outDir);
      exitCode = kExitOk;
      return;
    }
    FramePlan plan = framePlanFor(loaded.scene, framePlanFlags(*args), processEnvironment);
    if (plan.iterations > 1 || plan.shard.sharded() || args->resume)
      throw SceneError(SourceLoc{"--no-render", 0, 0},
                       "--no-render plays one iteration of the whole timeline; it takes no --iterations, shard or "
                       "--resume (found iterations " + std::to_string(plan.iterations) + ", shard " +
                           std::to_string(plan.shard.index) + "/" + std::to_string(plan.shard.count) + ")");
    TimelineRunOptions options;
    options.frames = plan.framesPerIteration;
    options.seed = args->seed.value_or(loaded.scene.capture.getInt("seed"));
    options.recordPath = args->record;
    options.saveStagePath = args->saveStage;
    TimelineRunResult result = runTimeline(loaded, options);
    log::info(args->scene.scene + ": " + std::to_string(result.frames) + " frames, " +
              std::to_string(result.behaviors) + " behaviors, " + std::to_string(result.updates) + " updates" +
              (args->record.empty() ? "" : "; changes recorded in " + args->record));
    exitCode = kExitOk;
  });
}

}  // namespace sdg::cli
