#pragma once
// `sdgbehave merge DIR`: after every shard of a run has written into DIR,
// finalizes the dataset (manifest, COCO, contact sheet: the same bytes a
// whole run writes) and combines the shards' summaries into
// run_summary.json. A missing frame is a RunError naming it.
#include <string>

#include <nlohmann/json.hpp>

namespace sdg {

struct MergeResult {
  uint64_t frames = 0;
  uint64_t shards = 0;  // shard summaries found
  uint64_t files = 0;   // the dataset's files outside .sdgbehave/, as run_summary.json's files_written
  nlohmann::ordered_json summary;
};

MergeResult mergeShards(const std::string& dir);

}  // namespace sdg
