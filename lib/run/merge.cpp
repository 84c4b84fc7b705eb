#include "run/merge.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/diagnostics.h"
#include "core/file_io.h"
#include "core/text.h"
#include "run/dataset_finalize.h"
#include "writers/manifest.h"

namespace sdg {
namespace fs = std::filesystem;

namespace {

std::vector<nlohmann::ordered_json> shardSummaries(const std::string& dir) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(fs::path(dir) / kPartsFolder, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("summary.", 0) == 0 && e.path().extension() == ".json") files.push_back(e.path());
  }
  std::vector<nlohmann::ordered_json> out;
  for (const fs::path& f : files) {
    std::ifstream in(f);
    std::stringstream text;
    text << in.rdbuf();
    auto j = nlohmann::ordered_json::parse(text.str(), nullptr, false);
    if (!j.is_discarded() && j.is_object() && j.contains("shard")) out.push_back(std::move(j));
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
    return a["shard"]["index"].template get<uint64_t>() < b["shard"]["index"].template get<uint64_t>();
  });
  return out;
}

}  // namespace

MergeResult mergeShards(const std::string& dir) {
  const RunInfo info = readRunInfo(dir);
  // Shards that ran with other inputs (a script edited between two shards'
  // starts) would make one dataset of two runs: refuse, naming the files.
  if (std::vector<std::string> problems = shardInputProblems(dir, info); !problems.empty())
    throw SceneError(SourceLoc{dir, 0, 0}, "the shards did not all run with the same inputs:\n  " +
                                               text::join(problems, "\n  ") +
                                               "\nrerun those shards with the run's inputs (--resume), then merge again");
  FinalizeResult finalized = finalizeDataset(dir, info);
  // Checked: the per-shard records go, as the per-shard manifests do, so a
  // merged folder holds the same files as a whole run's.
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(fs::path(dir) / kPartsFolder, ec)) {
    const std::string name = e.path().filename().string();
    if (name.starts_with("inputs.") && name.ends_with(".json")) fs::remove(e.path(), ec);
  }
  MergeResult result;
  result.frames = finalized.frames;
  std::vector<nlohmann::ordered_json> shards = shardSummaries(dir);
  result.shards = shards.size();

  // One summary for the dataset: the run's identity, and per shard what it did.
  nlohmann::ordered_json j;
  j["tool"] = "sdgbehave";
  j["merged_from_shards"] = shards.size();
  if (!shards.empty()) {
    j["version"] = shards.front()["version"];
    j["scene"] = shards.front()["scene"];
    // Every shard loads the same scene: its losses are the first shard's.
    if (shards.front().contains("dropped")) j["dropped"] = shards.front()["dropped"];
  }
  j["scene_hash"] = info.sceneHash;
  j["inputs_identity"] = info.inputs.identity();
  j["seed"] = info.seed;
  j["frames"] = info.frames();
  j["iterations"] = info.iterations;
  j["frames_per_iteration"] = info.framesPerIteration;
  j["output"] = dir;
  // As a whole run counts them: the folder's files (shards write the same
  // run files, so their counts do not add up) and this summary, about to be.
  const bool summaryExists = fs::exists(fs::path(dir) / "run_summary.json", ec);
  result.files = countDatasetFiles(dir) + (summaryExists ? 0 : 1);
  j["files_written"] = result.files;
  nlohmann::ordered_json settle = nlohmann::ordered_json::array(), perShard = nlohmann::ordered_json::array();
  double busiest = 0;
  for (const auto& s : shards) {
    for (const auto& r : s["settle"]) settle.push_back(r);
    double total = s["seconds"]["total"].get<double>();
    busiest = std::max(busiest, total);
    perShard.push_back({{"shard", s["shard"]}, {"frames", s["frames"]}, {"frames_resumed", s["frames_resumed"]},
                        {"pre_rolls", s["pre_rolls"]}, {"seconds", s["seconds"]}, {"peak_rss_mb", s["peak_rss_mb"]}});
    if (s.contains("warnings") && !s["warnings"].empty()) perShard.back()["warnings"] = s["warnings"];
  }
  j["slowest_shard_seconds"] = busiest;
  j["shards"] = std::move(perShard);
  j["settle"] = std::move(settle);
  writeFileAtomic((fs::path(dir) / "run_summary.json").string(), j.dump(2) + "\n");
  result.summary = std::move(j);
  return result;
}

}  // namespace sdg
