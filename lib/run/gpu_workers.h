#pragma once
// `sdgbehave run --gpus all|N|LIST`: one worker process per GPU on one
// machine (a render box), each `run --gpu g --shard i/k --threads
// cores/k` into the same folder, one progress line for all, every worker
// stopped on the first failure (frames finished stay, for --resume), and
// the shards merged at the end into exactly the dataset one process writes.
// A convenience on one box; Slurm and Kubernetes stay the way across boxes.
#include <cstdint>
#include <string>
#include <vector>

namespace sdg {

// The GPUs `--gpus SPEC` names, as indices among those the process sees
// (render/egl: SDGBEHAVE_VISIBLE_GPUS applies): "all", a count N (the first
// N) or a list "0,2,3". SceneError (exit 2) located at --gpus when
// malformed or naming GPUs this machine lacks.
std::vector<int> gpusFromSpec(const std::string& spec);

struct GpuWorkersOptions {
  std::string executable;         // this program (/proc/self/exe)
  std::vector<std::string> args;  // `run` and its arguments, without --gpus, --gpu, --shard, --threads
  std::vector<int> gpus;          // two or more
  unsigned threads = 0;           // the cores to share (0 = all)
  std::string outDir;
  uint64_t totalFrames = 0;       // for the progress line
  bool progress = false;          // draw it (stderr is a terminal)
};

struct GpuWorkersResult {
  uint64_t frames = 0;
  uint64_t files = 0;
  double seconds = 0;
};

// Runs the workers to their end and merges. RunError when a worker fails
// (the others are stopped; its log's last lines are in the message) or the
// merge does; each worker's log is kept as <out>/.sdgbehave/worker.<shard
// tag>.log (while they run: in $TMPDIR/sdgbehave-gpus-<pid>/).
GpuWorkersResult runOnGpus(const GpuWorkersOptions& options);

}  // namespace sdg
