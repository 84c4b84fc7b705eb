#pragma once
// The output folder of a dataset run: who may write into it, the run
// description every shard shares (.sdgbehave/run.json), the hidden parts a
// frame writes besides the dataset's own files (COCO fragments, contact
// sheet tiles), and durable writes of a frame's files.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run/run_inputs.h"
#include "writers/output_files.h"

namespace sdg {

// What every process writing into one folder must agree on.
struct RunInfo {
  std::string sceneHash;
  int64_t seed = 0;
  uint64_t iterations = 1;
  uint64_t framesPerIteration = 1;
  int width = 0, height = 0;
  std::vector<std::string> products;
  std::string cocoFile;      // "" without a COCO writer
  std::string cocoTaxonomy;
  std::string bopSplit;      // "" without a BOP writer
  bool contactSheet = true;
  RunInputs inputs;  // every input file's hash and sdgbehave's version
  // No shard count: frames depend only on (scene, seed, iteration, frame),
  // so shards of different counts still write the same bytes.

  uint64_t frames() const { return iterations * framesPerIteration; }
  nlohmann::ordered_json toJson() const;
  static RunInfo fromJson(const nlohmann::json& j);
  bool operator==(const RunInfo&) const = default;
};

struct FolderPolicy {
  bool overwrite = false;  // replace an earlier run's files
  bool resume = false;     // keep the frames an earlier run finished
  bool sharded = false;    // other shards of this run may write here too
  std::string shardTag;    // this shard's name ("2-of-4"), when sharded
};

// Creates the folder or checks that this run may use it, then records
// `info` (SceneError for a folder holding something else, exit 2).
void prepareOutputFolder(const std::string& dir, const RunInfo& info, const FolderPolicy& policy);
// Records `info` again (a capture's frames are counted at its end).
void recordRunInfo(const std::string& dir, const RunInfo& info);
RunInfo readRunInfo(const std::string& dir);  // RunError when absent or corrupt
// Shards that started together can each find the folder empty; every shard
// therefore also records its own inputs (.sdgbehave/inputs.<tag>.json).
// One line per shard whose inputs differ from run.json's, naming the files.
std::vector<std::string> shardInputProblems(const std::string& dir, const RunInfo& info);
// Temporary files a killed run left behind ("*.tmp-<pid>").
void removeStaleTemporaries(const std::string& dir);

}  // namespace sdg
