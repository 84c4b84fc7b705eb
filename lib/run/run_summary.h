#pragma once
// run_summary.json: what a script or scheduler needs to know about a run.
// It is the one output file whose bytes differ between runs (timings).
#include <string>

#include <nlohmann/json.hpp>

#include "core/dropped.h"
#include "run/dataset_run.h"

namespace sdg {

struct RunSummaryInputs {
  std::string version;
  std::string scenePath;
  const Scene* scene = nullptr;
  const DatasetRunOptions* options = nullptr;
  const DatasetRunResult* result = nullptr;
  double loadSeconds = 0;
  const std::vector<DroppedWarning>* dropped = nullptr;  // LoadedScene::dropped
};

nlohmann::ordered_json makeRunSummary(const RunSummaryInputs& in);
// The files a run leaves in its folder outside .sdgbehave/: what it wrote
// there, and run_summary.json itself unless the run is a shard (whose
// summary waits in .sdgbehave/ for merge). The run's log line,
// `files_written` and `sdgbehave verify`'s "N files" give this one count.
uint64_t datasetFilesWritten(const DatasetRunResult& result, bool sharded);
// Peak resident memory of this process, MB.
double peakRssMb();

}  // namespace sdg
