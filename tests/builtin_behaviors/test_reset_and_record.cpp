// Properties over every example scene: stop restores the stage exactly;
// the same seed gives the same record, another seed a different one.
#include "behavior/behavior_fixtures.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "run/timeline_run.h"
#include "scratch_name.h"

using namespace sdg;

namespace {
// Every scene under scenes/, plus the test scenes whose behaviors are
// scripts; `random` keeps only those whose behaviors draw random numbers.
std::vector<std::string> exampleScenes(bool random = false) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(SDG_SOURCE_DIR "/scenes"))
    // camera_rig.yaml holds only a look-at: nothing in it is random.
    if (e.path().extension() == ".yaml" && !(random && e.path().filename() == "camera_rig.yaml"))
      out.push_back(e.path().string());
  // Scenes whose behaviors are scripts, beside those in scenes/examples/.
  out.push_back(SDG_SOURCE_DIR "/tests/data/scripts/determinism.yaml");
  if (!random) out.push_back(SDG_SOURCE_DIR "/tests/data/scripts/events.yaml");
  std::sort(out.begin(), out.end());
  return out;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string recordOf(const std::string& scene, int64_t seed) {
  LoadedScene loaded = loadSceneForRun(SceneRequest{.scenePath = scene});
  std::string path = test::uniqueTempPath("sdg_record_" + std::to_string(seed)).string() + ".jsonl";
  runTimeline(loaded, TimelineRunOptions{12, seed, path, ""});
  std::string text = readFile(path);
  std::filesystem::remove(path);
  return text;
}
}  // namespace

TEST_CASE("reset: after stop every example scene's stage equals the stage before play", "[behaviors][reset]") {
  for (const std::string& scene : exampleScenes()) {
    CAPTURE(scene);
    LoadedScene loaded = loadSceneForRun(SceneRequest{.scenePath = scene});
    Stage original = loaded.scene.stage;
    TimelineRunResult result = runTimeline(loaded, TimelineRunOptions{12, 5, "", ""});
    CHECK(result.stageRestored);
    CHECK(loaded.scene.stage == original);
  }
}

TEST_CASE("determinism: the same seed gives the same record, another seed another record", "[behaviors][determinism]") {
  for (const std::string& scene : exampleScenes(/*random=*/true)) {
    CAPTURE(scene);
    std::string a = recordOf(scene, 10);
    CHECK(a == recordOf(scene, 10));
    bool randomized = a.find("changes\":[{") != std::string::npos;
    // Every example with random behaviors must react to the seed.
    if (randomized) CHECK(a != recordOf(scene, 11));
  }
}
