#pragma once
// The state behind `sdgbehave studio`: the scene's text with the edits not
// saved yet, the loaded scene, the stage after the pre-roll, and a renderer.
// An edit is a change of the text (studio/yaml_text_edit.h), checked by
// loading it like any scene; a change that only touches the timeline is
// carried over to the stage after the pre-roll, so the preview updates
// without stacking again (changes to event-driven behaviors mark the
// pre-roll stale until preroll() runs). Files are resolved only inside the
// scene's folder and asset roots (SceneRequest::confineAssets), so a value
// typed in the page opens nothing elsewhere. Render, writers and scripts
// are reached through run/. Not thread-safe: the server runs every call on
// one thread (the one that owns the GL context and Python).
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run/frame_plan.h"
#include "run/quick_render.h"
#include "run/scene_setup.h"

namespace sdg::studio {

// A request the page got wrong: the server answers 400 (409 for conflicts,
// 404 for something missing).
struct StudioError : std::runtime_error {
  StudioError(int status, const std::string& message) : std::runtime_error(message), status(status) {}
  int status;
};

struct StudioOptions {
  SceneRequest scene;
  RenderOverrides render;
};

class StudioSession {
 public:
  // Loads the scene (SceneError for an invalid one) and plays its pre-roll.
  explicit StudioSession(StudioOptions options);
  ~StudioSession();

  // The scene file, absolute.
  const std::string& scenePath() const { return options_.scene.scenePath; }
  nlohmann::ordered_json state();
  // The prim tree with every prim's attributes and behaviors (each variable
  // with its type, value, default, doc, bounds and origin).
  nlohmann::ordered_json tree();
  nlohmann::ordered_json behaviors();
  // Sets prim.keys (["size"] or ["behaviors", ns, variable]) to a JSON
  // value: in the scene file (a local override for a smart asset's value),
  // or, with `inAsset`, in the asset file the value comes from.
  nlohmann::ordered_json edit(const std::string& prim, const std::vector<std::string>& keys,
                              const std::string& jsonValue, bool inAsset = false);
  // Attaches (`attach`) or detaches a behavior: its entry is removed from
  // the prim's behaviors: and, if the result is not yet what was asked,
  // written as `{}` (attach) or `{enabled: false}` (detaching one a
  // referenced asset brings). The pre-roll runs again.
  nlohmann::ordered_json setAttached(const std::string& prim, const std::string& behavior, bool attach);
  // The camera's picture of frame `frame` (0-based: after frame + 1 updates):
  // pass rgb, semantic, instance, boxes or depth (run/quick_render.h, the
  // path `sdgbehave render` takes). PNG bytes.
  std::vector<uint8_t> preview(uint64_t frame, const std::string& pass, const std::string& camera);
  // What each behavior changed in that frame.
  nlohmann::ordered_json record(uint64_t frame);
  nlohmann::ordered_json preroll();
  void setSeed(int64_t seed);
  // The unsaved changes, one section per file. During a conflict the scene
  // file has two: what changed on disk since it was read, then what
  // overwriting it with the edits here would change.
  std::string diff() const;
  // The frame plan of a run with --frames `frames` (0: the scene's), as
  // `sdgbehave run` decides it, schedulers' variables ignored.
  FramePlan framePlan(uint64_t frames) const;
  // Files of a kind ("mesh" or "image") under the scene's asset roots, as
  // the scene would name them, for the page's asset fields.
  nlohmann::ordered_json files(const std::string& kind) const;
  // What a `sdgbehave run` of the scene as edited needs: its text and the
  // command-line flags the studio was started with (and the seed).
  const std::string& text() const { return text_; }
  std::vector<std::string> runFlags() const;
  // Writes the edited files. During a conflict (or when an asset file
  // edited here changed on disk) it is refused with 409, unless
  // `overwrite`: then the edits here replace the files on disk.
  nlohmann::ordered_json save(bool overwrite = false);
  // Drops the unsaved edits and loads the files as they are on disk (the
  // way out of a conflict).
  nlohmann::ordered_json reload();
  // Picks up edits made to the file on disk (reloads when nothing is
  // unsaved here, else reports a conflict). Called before every request.
  void checkFile();

 private:
  void load(const std::string& text);
  // StudioError 409 while the file on disk and the unsaved edits here differ.
  void refuseDuringConflict() const;
  // Loads `edited` as the scene (StudioError 400 with the loader's messages
  // when it does not load; nothing changes then).
  std::unique_ptr<LoadedScene> check(const std::string& edited,
                                     const std::map<std::string, std::string>& assetTexts);
  // Takes a checked candidate: carries its changes over to the stage after
  // the pre-roll (or marks the pre-roll stale) and makes it current.
  nlohmann::ordered_json adopt(std::unique_ptr<LoadedScene> candidate);
  std::map<std::string, std::string> assetTexts() const;
  bool unsaved() const;
  void runPreroll();
  std::unique_ptr<Stage> stageAt(uint64_t frame, std::optional<Stage>* before);

  StudioOptions options_;
  std::string diskText_;  // the file as last read or saved
  std::string conflictText_;  // during a conflict: the file as it is on disk now
  std::string text_;      // with the edits
  int64_t diskStamp_ = 0;
  std::map<std::string, int64_t> scriptStamps_;  // behavior scripts, watched like the scene
  struct AssetFile {
    std::string disk, text;  // as read, and with the edits made "in the asset"
  };
  std::map<std::string, AssetFile> assetFiles_;  // by assetKey()
  std::unique_ptr<LoadedScene> loaded_;
  std::unique_ptr<Stage> afterPreroll_;
  nlohmann::ordered_json settle_ = nlohmann::ordered_json::array();
  int64_t seed_ = 0;
  bool prerollStale_ = false;
  bool conflict_ = false;
  std::string reloadNote_;
  PictureRenderer pictures_;
};

}  // namespace sdg::studio
