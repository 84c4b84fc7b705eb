#include "run/output_folder.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/diagnostics.h"
#include "core/file_io.h"
#include "core/text.h"

namespace sdg {
namespace fs = std::filesystem;

namespace {

const SourceLoc kOut{"--out", 0, 0};

std::string runInfoPath(const std::string& dir) { return (fs::path(dir) / kPartsFolder / "run.json").string(); }

}  // namespace

nlohmann::ordered_json RunInfo::toJson() const {
  nlohmann::ordered_json j;
  j["format"] = 1;
  j["scene_hash"] = sceneHash;
  j["seed"] = seed;
  j["iterations"] = iterations;
  j["frames_per_iteration"] = framesPerIteration;
  j["resolution"] = {width, height};
  j["products"] = products;
  j["coco_file"] = cocoFile;
  j["coco_taxonomy"] = cocoTaxonomy;
  if (!bopSplit.empty()) j["bop_split"] = bopSplit;  // absent without BOP: earlier runs' run.json stay valid
  j["contact_sheet"] = contactSheet;
  j["inputs"] = inputs.toJson();
  return j;
}

RunInfo RunInfo::fromJson(const nlohmann::json& j) {
  RunInfo info;
  info.sceneHash = j.at("scene_hash").get<std::string>();
  info.seed = j.at("seed").get<int64_t>();
  info.iterations = j.at("iterations").get<uint64_t>();
  info.framesPerIteration = j.at("frames_per_iteration").get<uint64_t>();
  info.width = j.at("resolution").at(0).get<int>();
  info.height = j.at("resolution").at(1).get<int>();
  info.products = j.at("products").get<std::vector<std::string>>();
  info.cocoFile = j.at("coco_file").get<std::string>();
  info.cocoTaxonomy = j.at("coco_taxonomy").get<std::string>();
  if (j.contains("bop_split")) info.bopSplit = j.at("bop_split").get<std::string>();
  info.contactSheet = j.at("contact_sheet").get<bool>();
  if (j.contains("inputs")) info.inputs = RunInputs::fromJson(j.at("inputs"));
  return info;
}

void recordRunInfo(const std::string& dir, const RunInfo& info) {
  writeFileAtomic(runInfoPath(dir), info.toJson().dump(2) + "\n");
}

RunInfo readRunInfo(const std::string& dir) {
  std::ifstream in(runInfoPath(dir));
  if (!in) throw RunError(dir + " holds no sdgbehave run (" + runInfoPath(dir) + " is missing)");
  std::stringstream text;
  text << in.rdbuf();
  nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, false);
  const std::string corrupt = runInfoPath(dir) + " is corrupt; delete the folder's .sdgbehave/ to start over";
  if (j.is_discarded()) throw RunError(corrupt);
  try {
    return RunInfo::fromJson(j);
  } catch (const nlohmann::json::exception&) {
    throw RunError(corrupt);
  }
}

void prepareOutputFolder(const std::string& dir, const RunInfo& info, const FolderPolicy& policy) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) throw SceneError(kOut, dir + " exists and is not a folder");
  const bool empty = !fs::exists(dir, ec) || fs::is_empty(dir, ec);
  if (!empty) {
    bool hasRun = fs::exists(runInfoPath(dir), ec);
    // Shards start together: another may have made the folder and not yet
    // written run.json. Give it a moment rather than refusing the folder.
    for (int i = 0; policy.sharded && !hasRun && fs::exists(fs::path(dir) / kPartsFolder, ec) && i < 100; ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      hasRun = fs::exists(runInfoPath(dir), ec);
    }
    if (policy.overwrite) {
      if (policy.sharded)
        throw SceneError(kOut, "--overwrite cannot be used with shards (one shard would delete another's files); "
                               "empty " + dir + " first, or use --resume");
      // The old run's bookkeeping goes; its data files are replaced as frames are written.
      fs::remove_all(fs::path(dir) / kPartsFolder, ec);
      for (const auto& e : fs::directory_iterator(dir, ec))
        if (e.path().filename().string().rfind("manifest", 0) == 0) fs::remove(e.path(), ec);
    } else if (hasRun && (policy.resume || policy.sharded)) {
      RunInfo existing = readRunInfo(dir);
      if (!(existing.inputs == info.inputs))
        throw SceneError(kOut, dir + " holds a run of other inputs; these changed since it began:\n  " +
                                   text::join(inputChanges(existing.inputs, info.inputs), "\n  ") +
                                   "\nrestore them, or start the run again in another folder (or with --overwrite)");
      RunInfo settings = existing;
      settings.inputs = info.inputs;
      if (!(settings == info))
        throw SceneError(kOut, dir + " holds a different run (" + existing.toJson().dump() +
                                   "); use the same scene, seed and flags, or another folder");
    } else {
      throw SceneError(kOut, dir + " is not empty; choose another folder, pass --overwrite to replace its files" +
                                 std::string(hasRun ? ", or --resume to finish the run it holds" : ""));
    }
  }
  fs::create_directories(fs::path(dir) / kPartsFolder, ec);
  if (ec) throw RunError("cannot create the output folder " + dir + ": " + ec.message());
  writeFileAtomic(runInfoPath(dir), info.toJson().dump(2) + "\n");
  if (policy.sharded)
    writeFileAtomic((fs::path(dir) / kPartsFolder / ("inputs." + policy.shardTag + ".json")).string(),
                    info.inputs.toJson().dump(2) + "\n");
}

std::vector<std::string> shardInputProblems(const std::string& dir, const RunInfo& info) {
  std::vector<std::string> problems;
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(fs::path(dir) / kPartsFolder, ec)) {
    const std::string name = e.path().filename().string();
    if (name.starts_with("inputs.") && name.ends_with(".json")) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, false);
    const std::string shard = file.filename().string().substr(7, file.filename().string().size() - 12);
    const std::string corrupt = "shard " + shard + ": " + file.string() + " is corrupt";
    if (j.is_discarded()) {
      problems.push_back(corrupt);
      continue;
    }
    RunInputs inputs;
    try {
      inputs = RunInputs::fromJson(j);
    } catch (const nlohmann::json::exception&) {
      problems.push_back(corrupt);
      continue;
    }
    const std::vector<std::string> changes = inputChanges(info.inputs, inputs);
    if (!changes.empty()) problems.push_back("shard " + shard + " ran with other inputs: " + text::join(changes, "; "));
  }
  return problems;
}

void removeStaleTemporaries(const std::string& dir) {
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); it != fs::recursive_directory_iterator(); it.increment(ec))
    if (it->is_regular_file(ec) && it->path().filename().string().find(".tmp-") != std::string::npos)
      fs::remove(it->path(), ec);
}

}  // namespace sdg
