// The one entry point for scene files (scene_io/scene_source.h): a YAML
// scene and a USD stage read through the same call, with every script file
// the scene names asked of the caller's SceneScriptHost (where and in what
// order), never guessed from the file's text. The host here loads nothing:
// it answers for Isaac's six by file name, as the built-ins stand in, and
// records what it was asked; the real host (run/) is exercised by the
// end-to-end tests (scripts.*, usd.*).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "builtin_behaviors/builtin_behaviors.h"
#include "scene_io/scene_source.h"
#include "scene_io/usd_prim_labels.h"

namespace sdg {
namespace {

const std::string kData = std::string(SDG_SOURCE_DIR) + "/tests/data/";

class RecordingHost : public SceneScriptHost {
 public:
  const BehaviorCatalog& catalog() const override { return catalog_; }
  void loadScript(const std::string& path, const SourceLoc&) override { calls.push_back("script " + path); }
  void loadPlugin(const std::string& path, const SourceLoc&) override { calls.push_back("plugin " + path); }
  void sceneIsaacScripts(std::optional<IsaacScriptChoice> setting) override {
    calls.push_back(setting ? "isaac_scripts said" : "isaac_scripts unsaid");
  }
  std::vector<std::string> attach(const std::string& path, const SourceLoc& where) override {
    calls.push_back("attach " + std::filesystem::path(path).filename().string() + " at " + where.str());
    const std::string builtin = builtinForIsaacScript(std::filesystem::path(path).filename().string());
    if (builtin.empty()) throw SceneError(where, "omni:scripting:scripts: cannot attach " + path);
    catalog_.attachedScripts[path] = {builtin};
    return {builtin};
  }
  std::vector<std::string> calls;

 private:
  BehaviorCatalog catalog_ = builtinRegistry().catalog();
};

}  // namespace

TEST_CASE("scene source: a USD stage's listed scripts are attached through the host, located", "[scene_io]") {
  const std::string stage = "#usda 1.0\n(\n    metersPerUnit = 1\n    upAxis = \"Z\"\n)\ndef Cube \"Box\"\n{\n"
                            "    asset[] omni:scripting:scripts = [@/isaac/behaviors/location_randomizer.py@]\n"
                            "    custom uint exposedVar:locationRandomizer:interval = 3\n}\n";
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "sdg_scene_source_test";
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "box.usda").string();
  {
    std::ofstream(file) << stage;
  }
  RecordingHost host;
  const SceneSourceRead read = readSceneSource(SceneSource{file, std::nullopt, {}, {}}, host);
  REQUIRE(host.calls.size() == 2);
  CHECK(host.calls[0] == "isaac_scripts unsaid");
  CHECK(host.calls[1] == "attach location_randomizer.py at " + file + ":8:5");
  const Prim* box = read.scene.stage.find("/Box");
  REQUIRE(box != nullptr);
  CHECK(box->behaviors() == std::vector<std::string>{"locationRandomizer"});
  CHECK(box->findAttribute("exposedVar:locationRandomizer:interval")->value == Value::makeUInt(3));
  CHECK(read.mountedFiles == std::vector<std::string>{std::filesystem::absolute(file).lexically_normal().string()});

  SECTION("the host's refusal is the scene's error, at the listing") {
    const std::string other = (dir / "other.usda").string();
    {
      std::ofstream(other) << "#usda 1.0\ndef Cube \"Box\"\n{\n    asset[] omni:scripting:scripts = [@/x/my_thing.py@]\n}\n";
    }
    RecordingHost refusing;
    CHECK_THROWS_WITH(readSceneSource(SceneSource{other, std::nullopt, {}, {}}, refusing),
                      Catch::Contains(other + ":4:5") && Catch::Contains("cannot attach /x/my_thing.py"));
  }
  std::filesystem::remove_all(dir);
}

TEST_CASE("scene source: a YAML scene mounting a USD stage attaches the stage's listed files before building",
          "[scene_io]") {
  // scripted_mount.yaml mounts scripted_prop.usda, whose camera lists a
  // script: the host is asked for it at the reference that mounts the file.
  RecordingHost host;
  const std::string yaml = kData + "usd/scripted_mount.yaml";
  CHECK_THROWS_WITH(readSceneSource(SceneSource{yaml, std::nullopt, {}, {}}, host),
                    Catch::Contains("scripted_mount.yaml:5:") && Catch::Contains("cannot attach") &&
                        Catch::Contains("camera_orbit.py"));
  REQUIRE(host.calls.size() == 2);
  CHECK(host.calls[0] == "isaac_scripts unsaid");
  CHECK_THAT(host.calls[1], Catch::StartsWith("attach camera_orbit.py at ") && Catch::Contains("scripted_mount.yaml:5:"));
}

TEST_CASE("scene source: the studio's unsaved text is read as YAML under the file's name", "[scene_io]") {
  RecordingHost host;
  const SceneSourceRead read = readSceneSource(
      SceneSource{"/nowhere/edited.yaml", std::string("version: 1\nprims:\n  /World: {type: Xform}\n"), {"/World.visibility=invisible"}, {}},
      host);
  CHECK(read.scene.stage.find("/World")->getString("visibility") == "invisible");
  CHECK(read.scene.sourcePath == "/nowhere/edited.yaml");
}

}  // namespace sdg
