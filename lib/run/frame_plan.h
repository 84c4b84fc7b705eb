#pragma once
// Which frames a run captures and which of them this process owns.
// Frames are numbered 0 .. iterations x framesPerIteration - 1 across
// iterations; shard i of k owns the contiguous block
// [total * i / k, total * (i + 1) / k), so a shard touches as few iterations
// (pre-rolls) as possible and a shard with an empty block has nothing to do.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace sdg {

struct Scene;

struct ShardSpec {
  uint64_t index = 0;
  uint64_t count = 1;
  bool sharded() const { return count > 1; }
  // "shard-2-of-4", used in file names.
  std::string tag() const;
};

// Documented limit on frames per run (iterations x frames per iteration);
// nothing is allocated per frame, this only keeps the arithmetic exact.
inline constexpr uint64_t kMaxRunFrames = uint64_t(1) << 50;

struct FramePlan {
  uint64_t iterations = 1;
  uint64_t framesPerIteration = 1;
  ShardSpec shard;

  uint64_t total() const { return iterations * framesPerIteration; }
  // 128-bit products: total x index must not wrap for any shard count.
  uint64_t ownedBegin() const { return blockStart(shard.index); }
  uint64_t ownedEnd() const { return blockStart(shard.index + 1); }
  bool owns(uint64_t frame) const { return frame >= ownedBegin() && frame < ownedEnd(); }

 private:
  uint64_t blockStart(uint64_t index) const {
    __extension__ using Wide = unsigned __int128;
    return static_cast<uint64_t>(static_cast<Wide>(total()) * index / shard.count);
  }
};

using EnvLookup = std::function<std::optional<std::string>(const char*)>;

// The shard from the flags, else from the scheduler's environment: Slurm
// job arrays (SLURM_ARRAY_TASK_ID/_MIN/_STEP/_COUNT; unevenly spaced arrays
// are refused), then Kubernetes Indexed Jobs (JOB_COMPLETION_INDEX, with the
// count from --shard-count). Throws SceneError (exit 2) for inconsistent
// input, naming the variable or flag.
ShardSpec resolveShard(std::optional<uint64_t> flagIndex, std::optional<uint64_t> flagCount, const EnvLookup& env);

// What a command's flags ask of the frame plan (each unset: the scene decides).
struct FramePlanFlags {
  std::optional<uint64_t> frames;      // --frames: frames per iteration
  std::optional<uint64_t> iterations;  // --iterations
  std::string shard;                   // --shard i/k ("" = none)
  std::optional<uint64_t> shardIndex, shardCount;
};

// The one place a run's frames are decided, for `run` and the studio:
// frames per iteration from --frames, else capture.frames_per_iteration,
// else capture.frames; iterations from --iterations, else
// capture.iterations; the shard from the flags, else `env` (pass
// noEnvironment to ignore the schedulers). SceneError (exit 2) past
// kMaxRunFrames or for inconsistent shard input.
FramePlan framePlanFor(const Scene& scene, const FramePlanFlags& flags, const EnvLookup& env);

// "i/k" as given to --shard.
std::pair<uint64_t, uint64_t> parseShardFlag(const std::string& text);
// getenv as an EnvLookup.
std::optional<std::string> processEnvironment(const char* name);
// An EnvLookup where nothing is set.
std::optional<std::string> noEnvironment(const char* name);

}  // namespace sdg
