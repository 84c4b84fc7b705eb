#pragma once
// A run with pixels: pre-roll, play, and per frame one update, a render of
// every camera (render product), the annotators, and the writer's files
// encoded and written on a background pool while the next frame renders.
#include <cstdint>
#include <optional>
#include <string>

#include "run/scene_setup.h"

namespace sdg {

struct DatasetRunOptions {
  uint64_t frames = 1;
  int64_t seed = 0;
  std::string outDir;
  bool overwrite = false;
  unsigned threads = 0;  // 0 = one per core
  std::optional<int> width, height, subframes;
  std::string recordPath;
  std::string saveStagePath;  // --save-stage: the scene after the pre-roll
  bool progress = false;  // draw a progress bar on stderr
};

// Seconds spent in each stage of the run (encode+write summed over the
// pool's threads, so it can exceed the wall time).
struct StageTimes {
  double preroll = 0, behaviors = 0, render = 0, annotate = 0, encodeWrite = 0;
};

struct DatasetRunResult {
  uint64_t frames = 0;
  uint64_t files = 0;
  std::string renderer;
  std::string backend;
  double seconds = 0;  // wall time of the run (after loading)
  StageTimes stages;
  uint64_t simulationFrames = 0;  // renderSimulation images per camera
  std::vector<nlohmann::ordered_json> settle;  // settle quality per stacked surface
};

DatasetRunResult runDataset(LoadedScene& loaded, const DatasetRunOptions& options);

}  // namespace sdg
