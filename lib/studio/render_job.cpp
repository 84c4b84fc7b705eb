#include "studio/render_job.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <csignal>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "core/file_io.h"
#include "studio/studio_session.h"

extern char** environ;

namespace sdg::studio {
namespace fs = std::filesystem;

RenderJob::~RenderJob() {
  {
    std::lock_guard lock(mutex_);
    if (running_ && pid_ > 0) kill(pid_, SIGTERM);  // the studio stops: so does its render
  }
  if (waiter_.joinable()) waiter_.join();
}

void RenderJob::start(const std::string& scenePath, const std::string& text, uint64_t frames, uint64_t total,
                      const std::string& name, const std::vector<std::string>& extraArgs) {
  static const std::regex kName("[A-Za-z0-9_][A-Za-z0-9_.-]{0,63}");
  if (!std::regex_match(name, kName) || name.find("..") != std::string::npos)
    throw StudioError(400, "the output name is letters, digits, '_', '-' and '.', found '" + name + "'");
  if (frames < 1 || frames > 100000) throw StudioError(400, "frames must be 1 to 100000");
  std::lock_guard lock(mutex_);
  if (running_) throw StudioError(409, "a render is running already");
  if (waiter_.joinable()) waiter_.join();
  const fs::path dir = fs::path(scenePath).parent_path();
  out_ = (dir / "studio_out" / name).string();
  tempScene_ = (dir / ("." + fs::path(scenePath).filename().string() + ".studio-render.yaml")).string();
  writeFileAtomic(tempScene_, text);
  const std::string errorsPath = tempScene_ + ".log";
  std::vector<std::string> args = {fs::read_symlink("/proc/self/exe").string(), "run", tempScene_, "--frames",
                                   std::to_string(frames), "--out", out_, "--overwrite"};
  args.insert(args.end(), extraArgs.begin(), extraArgs.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, errorsPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  // The studio blocks SIGINT and SIGTERM in its threads: the child must not
  // inherit that, or it could not be stopped.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
  pid_t pid = 0;
  const int failed = posix_spawn(&pid, argv[0], &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (failed) {
    fs::remove(tempScene_);
    throw StudioError(500, "cannot start the render: " + std::string(strerror(failed)));
  }
  running_ = true;
  pid_ = pid;
  exitCode_ = -1;
  frames_ = total;
  errors_.clear();
  waiter_ = std::thread([this, pid, errorsPath] {
    int status = 0;
    waitpid(pid, &status, 0);
    std::ifstream log(errorsPath);
    std::stringstream text;
    text << log.rdbuf();
    std::error_code ec;
    fs::remove(errorsPath, ec);
    std::lock_guard lock(mutex_);
    fs::remove(tempScene_, ec);
    exitCode_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    errors_ = text.str();
    running_ = false;
  });
}

nlohmann::ordered_json RenderJob::status() {
  std::lock_guard lock(mutex_);
  nlohmann::ordered_json j;
  j["running"] = running_;
  j["out"] = out_;
  j["frames"] = frames_;
  uint64_t done = 0;
  std::error_code ec;
  if (!out_.empty() && fs::is_directory(out_, ec))
    for (const auto& e : fs::directory_iterator(out_, ec))
      if (e.path().filename().string().starts_with("rgb_")) ++done;
  j["frames_written"] = done;
  j["exit_code"] = running_ ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(exitCode_);
  if (!running_ && exitCode_ > 0) j["error"] = errors_.size() > 4000 ? errors_.substr(errors_.size() - 4000) : errors_;
  j["contact_sheet"] = !running_ && exitCode_ == 0 && fs::exists(fs::path(out_) / "contact_sheet.png", ec);
  return j;
}

std::string RenderJob::contactSheet() {
  std::lock_guard lock(mutex_);
  if (running_ || out_.empty()) throw StudioError(404, "no finished render");
  std::ifstream in(fs::path(out_) / "contact_sheet.png", std::ios::binary);
  if (!in) throw StudioError(404, "the render wrote no contact sheet");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace sdg::studio
