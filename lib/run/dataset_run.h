#pragma once
// A run with pixels. Per iteration: a fresh copy of the stage, the pre-roll,
// play, and per frame one update, a render of every camera (render
// product), the annotators, and the writer's files encoded and written on a
// background pool while the next frame renders. Behaviors step through
// every update of an iteration; only frames this shard owns (and, with
// --resume, has not finished) are rendered, so every frame's bytes depend
// only on (scene, seed, iteration, frame) and shards add up to the whole.
// With motion annotators (optical flow) a shard also steps the frame after
// its last owned one, whose poses that frame's forward flow needs. The
// writers come from the registry (writers/writer_registry.h); what they
// need decides the passes read back.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "run/frame_plan.h"
#include "run/output_folder.h"
#include "run/scene_setup.h"

namespace sdg {

struct DatasetRunOptions {
  FramePlan plan;
  int64_t seed = 0;
  std::string outDir;
  bool overwrite = false;
  bool resume = false;  // keep frames the manifest lists whose files still match
  unsigned threads = 0;  // 0 = one per core
  RenderOverrides render;
  std::string recordPath;
  std::string saveStagePath;  // --save-stage: the scene after the pre-roll
  bool progress = false;  // draw a progress bar on stderr
};

// Seconds spent in each stage of the run (annotate and encode+write run on
// the pool and are summed over its threads, so they can exceed the wall time).
struct StageTimes {
  double preroll = 0, behaviors = 0, render = 0, annotate = 0, encodeWrite = 0;
};

struct DatasetRunResult {
  uint64_t frames = 0;         // frames rendered by this process
  uint64_t resumedFrames = 0;  // owned frames kept from an earlier run
  uint64_t iterationsRun = 0;  // pre-rolls this process ran
  bool finalized = false;      // COCO, contact sheet and manifest written (not for shards)
  RunInfo info;
  uint64_t files = 0;
  std::string renderer;
  std::string backend;
  std::string device;
  std::string colorDevice;  // what made the colour: the rasterizer, or a path tracer and its device
  double seconds = 0;  // wall time of the run (after loading)
  StageTimes stages;
  uint64_t simulationFrames = 0;  // renderSimulation images per camera
  std::vector<nlohmann::ordered_json> settle;  // settle quality per stacked surface
  // Said once each while running: no semantic label on the stage, a black frame.
  std::vector<std::string> warnings;
};

DatasetRunResult runDataset(LoadedScene& loaded, const DatasetRunOptions& options);

class DatasetRun;

// Frames taken when something else says so (`sdgbehave exec`: Replicator's
// orchestrator.step from a driver program): the loaded scene's stage as it
// stands at each capture() is the next frame, rendered and written as a
// run's frames are (the writers, products and resolution from the loaded
// scene and `options.render`; no pre-roll, no behaviors: the caller drives
// the stage). finish() writes what is queued and finalizes the folder, whose
// run.json then records the frames taken. `options.plan` is not used.
class DatasetCapture {
 public:
  DatasetCapture(LoadedScene& loaded, DatasetRunOptions options);
  ~DatasetCapture();
  DatasetCapture(const DatasetCapture&) = delete;
  DatasetCapture& operator=(const DatasetCapture&) = delete;

  void capture();
  uint64_t frames() const;
  DatasetRunResult finish();

 private:
  std::unique_ptr<DatasetRunOptions> options_;
  std::unique_ptr<DatasetRun> run_;
};

}  // namespace sdg
