#include "run/frame_plan.h"

#include <cstdlib>

#include "core/diagnostics.h"
#include "scene_io/scene.h"

namespace sdg {
namespace {

SourceLoc at(const std::string& what) { return SourceLoc{what, 0, 0}; }

uint64_t parseCount(const std::string& text, const std::string& what) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos || text.size() > 18)
    throw SceneError(at(what), "expected a whole number, found '" + text + "'");
  return std::stoull(text);
}

}  // namespace

std::string ShardSpec::tag() const { return "shard-" + std::to_string(index) + "-of-" + std::to_string(count); }

std::optional<std::string> processEnvironment(const char* name) {
  const char* v = std::getenv(name);
  if (!v) return std::nullopt;
  return std::string(v);
}

std::optional<std::string> noEnvironment(const char*) { return std::nullopt; }

FramePlan framePlanFor(const Scene& scene, const FramePlanFlags& flags, const EnvLookup& env) {
  FramePlan plan;
  const uint32_t perIteration = scene.capture.getUInt("frames_per_iteration");
  plan.framesPerIteration = flags.frames.value_or(perIteration ? perIteration : scene.capture.getUInt("frames"));
  plan.iterations = flags.iterations.value_or(scene.capture.getUInt("iterations"));
  if (plan.framesPerIteration && plan.iterations > kMaxRunFrames / plan.framesPerIteration)
    throw SceneError(at("--iterations"),
                     std::to_string(plan.iterations) + " iterations x " + std::to_string(plan.framesPerIteration) +
                         " frames is beyond the limit of 2^50 frames per run; split the dataset into several runs");
  std::optional<uint64_t> index = flags.shardIndex, count = flags.shardCount;
  if (!flags.shard.empty()) {
    if (index || count) throw SceneError(at("--shard"), "give --shard i/k or --shard-index/--shard-count, not both");
    auto [i, k] = parseShardFlag(flags.shard);
    index = i, count = k;
  }
  plan.shard = resolveShard(index, count, env);
  return plan;
}

std::pair<uint64_t, uint64_t> parseShardFlag(const std::string& text) {
  size_t slash = text.find('/');
  if (slash == std::string::npos) throw SceneError(at("--shard"), "expected INDEX/COUNT such as 2/4, found '" + text + "'");
  return {parseCount(text.substr(0, slash), "--shard"), parseCount(text.substr(slash + 1), "--shard")};
}

ShardSpec resolveShard(std::optional<uint64_t> flagIndex, std::optional<uint64_t> flagCount, const EnvLookup& env) {
  ShardSpec spec;
  std::optional<uint64_t> index = flagIndex, count = flagCount;
  std::string source = "--shard-index/--shard-count";
  if (!index) {
    if (auto id = env("SLURM_ARRAY_TASK_ID")) {
      auto need = [&](const char* name) {
        auto v = env(name);
        if (!v) throw SceneError(at(name), std::string(name) + " is not set although SLURM_ARRAY_TASK_ID is");
        return parseCount(*v, name);
      };
      const uint64_t task = parseCount(*id, "SLURM_ARRAY_TASK_ID"), first = need("SLURM_ARRAY_TASK_MIN");
      const uint64_t last = need("SLURM_ARRAY_TASK_MAX"), step = need("SLURM_ARRAY_TASK_STEP");
      const uint64_t tasks = need("SLURM_ARRAY_TASK_COUNT");
      // Only an evenly spaced array maps tasks to 0..count-1 without gaps.
      if (step == 0 || (last - first) % step != 0 || (last - first) / step + 1 != tasks || (task - first) % step != 0)
        throw SceneError(at("SLURM_ARRAY_TASK_*"),
                         "the Slurm array is not evenly spaced (min " + std::to_string(first) + ", max " +
                             std::to_string(last) + ", step " + std::to_string(step) + ", count " +
                             std::to_string(tasks) + "); use --array=A-B[:S] or pass --shard i/k");
      index = (task - first) / step;
      if (!count) count = tasks;
      source = "SLURM_ARRAY_TASK_*";
    } else if (auto job = env("JOB_COMPLETION_INDEX")) {
      index = parseCount(*job, "JOB_COMPLETION_INDEX");
      source = "JOB_COMPLETION_INDEX";
      if (!count)
        throw SceneError(at("--shard-count"), "JOB_COMPLETION_INDEX is set (a Kubernetes Indexed Job) but the shard "
                                              "count is not: pass --shard-count (the Job's completions)");
    }
  }
  if (!index && !count) return spec;
  if (!index) throw SceneError(at("--shard-index"), "--shard-count needs --shard-index (or a scheduler's index)");
  if (!count) throw SceneError(at("--shard-count"), "--shard-index needs --shard-count");
  if (*count == 0) throw SceneError(at(source), "the shard count must be at least 1");
  if (*index >= *count)
    throw SceneError(at(source), "shard index " + std::to_string(*index) + " is not below the shard count " +
                                     std::to_string(*count));
  spec.index = *index;
  spec.count = *count;
  return spec;
}

}  // namespace sdg
