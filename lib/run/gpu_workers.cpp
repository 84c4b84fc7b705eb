#include "run/gpu_workers.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/diagnostics.h"
#include "core/log.h"
#include "render/egl/egl_devices.h"
#include "run/frame_plan.h"
#include "run/merge.h"
#include "run/output_folder.h"
#include "run/progress.h"

namespace sdg {
namespace fs = std::filesystem;

namespace {

const SourceLoc kFlag{"--gpus", 0, 0};

// The GPUs the process sees; with no libEGL, none (or, when `required`,
// a SceneError saying why).
int visibleGpuCount(bool required) {
  std::string why;
  const egl::Api* api = egl::api(&why);
  if (!api) {
    if (!required) return 0;
    throw SceneError(kFlag, "no GPU can be used: " + why);
  }
  std::string problem;
  const size_t n = egl::visibleGpus(*api, &problem).size();
  if (!problem.empty()) throw SceneError(kFlag, problem);
  return int(n);
}

struct Worker {
  pid_t pid = -1;
  int gpu = 0;
  ShardSpec shard;
  std::string log;
  int status = 0;
  bool done = false;
};

// The lines of a file (a worker's manifest): its finished frame outputs.
uint64_t lineCount(const std::string& path) {
  std::ifstream in(path);
  return uint64_t(std::count(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>(), '\n'));
}

std::string lastLines(const std::string& path, size_t count) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  std::string out;
  for (size_t i = lines.size() > count ? lines.size() - count : 0; i < lines.size(); ++i) out += "\n  " + lines[i];
  return out;
}

// fork + exec, the worker's output to its log; it gets SIGTERM when this
// process dies (Ctrl-C, a scheduler's cancel), so no worker outlives it.
pid_t spawn(const std::string& executable, const std::vector<std::string>& args, const std::string& logPath) {
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(executable.c_str()));
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const int logFd = ::open(logPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (logFd < 0) throw RunError("cannot create the worker log " + logPath);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    ::close(logFd);
    throw RunError("cannot start a worker process (fork failed)");
  }
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(143);  // the parent died before prctl took effect
    dup2(logFd, STDOUT_FILENO);
    dup2(logFd, STDERR_FILENO);
    execv(executable.c_str(), argv.data());
    _exit(127);
  }
  ::close(logFd);
  return pid;
}

int exitCodeOf(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return 1;
}

}  // namespace

std::vector<int> gpusFromSpec(const std::string& spec) {
  if (spec == "all") {
    std::vector<int> all(static_cast<size_t>(visibleGpuCount(false)));
    for (size_t i = 0; i < all.size(); ++i) all[i] = int(i);
    return all;
  }
  std::vector<int> listed;
  std::stringstream items(spec);
  for (std::string item; std::getline(items, item, ',');) {
    char* end = nullptr;
    const long v = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || v < 0 || v > 4096)
      throw SceneError(kFlag, "expected all, a number of GPUs or a list of GPU indices (0,2,3), found '" + spec + "'");
    listed.push_back(int(v));
  }
  if (listed.empty()) throw SceneError(kFlag, "expected all, a number of GPUs or a list of GPU indices, found ''");
  const int visible = visibleGpuCount(true);
  if (spec.find(',') == std::string::npos) {  // a count: the first N
    const int n = listed.front();
    if (n > visible)
      throw SceneError(kFlag, std::to_string(n) + " GPUs asked for; this process sees " + std::to_string(visible) +
                                  " (SDGBEHAVE_VISIBLE_GPUS restricts them)");
    std::vector<int> first(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) first[size_t(i)] = i;
    return first;
  }
  for (int g : listed)
    if (g >= visible)
      throw SceneError(kFlag, "GPU " + std::to_string(g) + " asked for; this process sees " + std::to_string(visible) +
                                  ", numbered from 0");
  std::vector<int> sorted = listed;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    throw SceneError(kFlag, "a GPU is listed twice in '" + spec + "'");
  return listed;
}

GpuWorkersResult runOnGpus(const GpuWorkersOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const size_t k = options.gpus.size();
  const unsigned cores = options.threads ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  const unsigned perWorker = std::max(1u, cores / unsigned(k));
  // The workers' logs wait outside the output folder (a shard finding the
  // folder's parts but no run.json takes it for another run's) and move
  // into its .sdgbehave/ once the run is merged.
  std::error_code ec;
  const fs::path logs = fs::temp_directory_path() / ("sdgbehave-gpus-" + std::to_string(getpid()));
  fs::create_directories(logs, ec);
  if (ec) throw RunError("cannot create " + logs.string() + " for the workers' logs: " + ec.message());
  std::vector<Worker> workers(k);
  for (size_t i = 0; i < k; ++i) {
    Worker& w = workers[i];
    w.gpu = options.gpus[i];
    w.shard = ShardSpec{i, k};
    w.log = (logs / ("worker." + w.shard.tag() + ".log")).string();
    std::vector<std::string> args = options.args;
    for (const std::string& a : {std::string("--gpu"), std::to_string(w.gpu), std::string("--shard"),
                                 std::to_string(i) + "/" + std::to_string(k), std::string("--threads"),
                                 std::to_string(perWorker)})
      args.push_back(a);
    w.pid = spawn(options.executable, args, w.log);
    log::debug("worker " + w.shard.tag() + " on GPU " + std::to_string(w.gpu) + ": pid " + std::to_string(w.pid));
  }
  Progress progress(options.totalFrames, options.progress);
  const Worker* failed = nullptr;
  size_t running = k, products = 0;
  while (running > 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    for (Worker& w : workers) {
      if (w.done) continue;
      int status = 0;
      if (waitpid(w.pid, &status, WNOHANG) != w.pid) continue;
      w.done = true;
      w.status = status;
      --running;
      if (exitCodeOf(status) != 0 && !failed) {
        failed = &w;
        for (Worker& other : workers)
          if (!other.done) kill(other.pid, SIGTERM);  // they keep their finished frames
      }
    }
    uint64_t frames = 0;
    for (const Worker& w : workers)
      frames += lineCount((fs::path(options.outDir) / ("manifest." + w.shard.tag() + ".jsonl")).string());
    if (products == 0) try {  // the render products, once a worker has recorded the run
        products = readRunInfo(options.outDir).products.size();
      } catch (const RunError&) {
      }
    progress.update(products ? frames / products : 0);
  }
  progress.finish();
  if (failed)
    throw RunError("the worker on GPU " + std::to_string(failed->gpu) + " (" + failed->shard.tag() + ") exited with " +
                   std::to_string(exitCodeOf(failed->status)) + "; the others were stopped, their finished frames kept "
                   "(--resume continues). Its log, " + failed->log + ", ends:" + lastLines(failed->log, 12));
  MergeResult merged = mergeShards(options.outDir);
  for (const Worker& w : workers) {
    const fs::path kept = fs::path(options.outDir) / kPartsFolder / fs::path(w.log).filename();
    fs::copy_file(w.log, kept, fs::copy_options::overwrite_existing, ec);
  }
  fs::remove_all(logs, ec);
  GpuWorkersResult result;
  result.frames = merged.frames;
  result.files = merged.files;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace sdg
