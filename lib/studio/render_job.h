#pragma once
// "Render N frames" from the studio page: an ordinary `sdgbehave run` of the
// scene as edited, in a child process (its own GL context and Python), into
// a folder under the scene's folder (studio_out/NAME). The edited text goes
// to a hidden file beside the scene, so relative paths resolve as in the
// scene, and is removed when the run ends. Progress is the number of rgb
// frames written so far.
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

namespace sdg::studio {

class RenderJob {
 public:
  RenderJob() = default;
  ~RenderJob();
  RenderJob(const RenderJob&) = delete;
  RenderJob& operator=(const RenderJob&) = delete;

  // Starts a run of `text` (the scene at `scenePath`, edited) with
  // --frames `frames` into <scene folder>/studio_out/<name>, which writes
  // `total` frames (the frame plan's: iterations x frames); `extraArgs`
  // are the studio's own --set/--plugin/--script/--asset-root/
  // --isaac-assets flags and seed. StudioError 409 while one runs, 400 for
  // a bad name or frame count.
  void start(const std::string& scenePath, const std::string& text, uint64_t frames, uint64_t total,
             const std::string& name, const std::vector<std::string>& extraArgs);
  nlohmann::ordered_json status();
  // The finished run's contact sheet (PNG bytes); StudioError 404 without one.
  std::string contactSheet();

 private:
  std::mutex mutex_;
  std::thread waiter_;
  bool running_ = false;
  int pid_ = 0;
  int exitCode_ = -1;
  std::string out_, tempScene_, errors_;
  uint64_t frames_ = 0;
};

}  // namespace sdg::studio
