#include "studio/studio_session.h"

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "assets/file_check.h"
#include "behavior/describe.h"
#include "behavior/runtime.h"
#include "core/file_io.h"
#include "core/text.h"
#include "run/preroll.h"
#include "scene_io/inspect.h"
#include "scene_io/references.h"
#include "scene_io/scene_loader.h"
#include "stage/prim_types.h"
#include "stage/stage_diff.h"
#include "stage/value_json.h"
#include "studio/yaml_text_edit.h"

namespace sdg::studio {
namespace {

using Json = nlohmann::ordered_json;

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw StudioError(409, "cannot read " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

int64_t stampOf(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return 0;
  return int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec + int64_t(st.st_size);
}

Json specJson(const AttributeSpec& spec) {
  Json j;
  j["type"] = std::string(valueTypeName(spec.type));
  j["default"] = valueToJson(spec.defaultValue);
  j["doc"] = spec.doc;
  if (spec.minimum) j["minimum"] = *spec.minimum;
  if (!spec.allowedTokens.empty()) j["allowed"] = spec.allowedTokens;
  if (spec.locked) j["locked"] = true;
  if (spec.primPath) j["prim_path"] = true;
  if (spec.files == FileKind::Mesh) j["files"] = "mesh";
  if (spec.files == FileKind::Image) j["files"] = "image";
  return j;
}

// The location with every file in it named by its absolute path. The
// loader names a smart asset below the working folder relative to it and
// one elsewhere absolutely; the page shows one style whatever the working
// folder. Pseudo-files ("--set[1]", a flag's name) are no files and stay.
SourceLoc absoluteLoc(const SourceLoc& loc) {
  SourceLoc out = loc;
  std::error_code ec;
  if (loc.known() && std::filesystem::is_regular_file(loc.file.str(), ec))
    out.file = std::filesystem::absolute(loc.file.str()).lexically_normal().string();
  if (loc.via) out.via = std::make_shared<const SourceLoc>(absoluteLoc(*loc.via));
  return out;
}

std::string origin(const SourceLoc& loc) { return valueOrigin(absoluteLoc(loc)); }

// A SceneError's problems, one a line, located with absolute paths.
std::string problemsText(const SceneError& e) {
  std::string messages;
  for (Diagnostic d : e.problems()) {
    d.loc = absoluteLoc(d.loc);
    messages += (messages.empty() ? "" : "\n") + d.format();
  }
  return messages;
}

Json attributeJson(const std::string& name, const Attribute& a, const AttributeSpec* spec) {
  Json j = spec ? specJson(*spec) : Json{{"type", std::string(valueTypeName(a.value.type()))}, {"doc", a.doc}};
  j["name"] = name;
  j["value"] = valueToJson(a.value);
  j["origin"] = origin(a.loc);
  return j;
}

// Every path the studio prints (origins, messages, the diff) is absolute:
// the scene is read through its absolute path, and nothing outside its
// folder and asset roots is resolved.
StudioOptions studioOptions(StudioOptions options) {
  options.scene.scenePath = std::filesystem::absolute(options.scene.scenePath).lexically_normal().string();
  options.scene.confineAssets = true;
  return options;
}

}  // namespace

StudioSession::StudioSession(StudioOptions options)
    : options_(studioOptions(std::move(options))), pictures_(options_.render, true) {
  diskText_ = readText(options_.scene.scenePath);
  diskStamp_ = stampOf(options_.scene.scenePath);
  load(diskText_);
  seed_ = loaded_->scene.capture.getInt("seed");
  runPreroll();
}

StudioSession::~StudioSession() = default;

void StudioSession::load(const std::string& text) {
  SceneRequest request = options_.scene;
  // A USD stage is read from its file (its text is not YAML); it reloads
  // when the file changes, and edits here are refused (refuseDuringConflict).
  if (!isUsdStagePath(request.scenePath)) request.sceneText = text;
  request.assetTexts = assetTexts();
  loaded_ = std::make_unique<LoadedScene>(loadSceneForRun(request));
  text_ = text;
  for (const std::string& script : loaded_->scriptFiles)
    if (!scriptStamps_.count(script)) scriptStamps_[script] = stampOf(script);
}

void StudioSession::runPreroll() {
  Stage stage = loaded_->scene.stage;
  RunBehaviorSetup setup;
  BehaviorContext context = behaviorContextFor(*loaded_, seed_, setup);
  {
    BehaviorRuntime runtime(stage, loaded_->registry, context);
    runtime.init();
    sdg::runPreroll(loaded_->scene.events, runtime);
    afterPreroll_ = std::make_unique<Stage>(stage);  // before the runtime's destroy puts things back
  }
  settle_ = Json::array();
  for (const auto& report : setup.reports) settle_.push_back(report);
  prerollStale_ = false;
}

void StudioSession::checkFile() {
  // A behavior script saved in an editor: run it again and reload the scene
  // with its new classes; one that no longer loads keeps the last good
  // version running and says why.
  bool scriptsChanged = false;
  for (auto& [script, stamp] : scriptStamps_) {
    const int64_t now = stampOf(script);
    if (now == stamp) continue;
    stamp = now;
    try {
      reloadBehaviorScript(script);
      scriptsChanged = true;
    } catch (const SceneError& e) {
      reloadNote_ = script + " no longer loads; the last good version keeps running:\n" + problemsText(e) + "\n";
    }
  }
  if (scriptsChanged) {
    try {
      load(text_);
      runPreroll();
      reloadNote_ = "reloaded: a behavior script changed on disk";
    } catch (const SceneError& e) {
      reloadNote_ = "the scene does not load with the changed script; the last good version keeps running:\n" +
                    problemsText(e) + "\n";
    }
  }
  const int64_t stamp = stampOf(options_.scene.scenePath);
  if (stamp == diskStamp_) return;
  diskStamp_ = stamp;
  std::string onDisk = readText(options_.scene.scenePath);
  if (onDisk == diskText_) {
    conflict_ = false;  // changed back: nothing to decide any more
    return;
  }
  if (unsaved()) {
    conflict_ = true;  // edits here and there: the user decides, nothing is overwritten
    conflictText_ = std::move(onDisk);
    return;
  }
  diskText_ = onDisk;
  try {
    load(onDisk);
    runPreroll();
    reloadNote_ = "reloaded: the file changed on disk";
  } catch (const SceneError& e) {
    text_ = onDisk;
    reloadNote_ = "the file changed on disk and does not load:\n" + problemsText(e) + "\n";
  }
}

Json StudioSession::state() {
  Json j;
  j["scene"] = options_.scene.scenePath;
  j["unsaved"] = unsaved();
  j["conflict"] = conflict_;
  j["preroll_stale"] = prerollStale_;
  j["seed"] = seed_;
  const FramePlan plan = framePlan(0);
  j["frames"] = plan.framesPerIteration;
  j["iterations"] = plan.iterations;
  Json cameras = Json::array();
  loaded_->scene.stage.traverse([&](const Prim& p) {
    if (p.type() == PrimType::Camera) cameras.push_back(p.path());
  });
  j["cameras"] = cameras;
  const auto& chosen = loaded_->scene.capture.get("cameras").get<std::vector<std::string>>();
  j["camera"] = chosen.empty() ? (cameras.empty() ? Json(nullptr) : cameras.front()) : Json(chosen.front());
  j["settle"] = settle_;
  j["note"] = reloadNote_;
  reloadNote_.clear();
  return j;
}

Json StudioSession::tree() {
  Json prims = Json::array();
  const BehaviorCatalog& catalog = loaded_->registry.catalog();
  loaded_->scene.stage.traverse([&](const Prim& p) {
    Json prim;
    prim["path"] = p.path();
    prim["type"] = std::string(p.typeInfo().name);
    prim["origin"] = origin(p.loc());
    Json attributes = Json::array();
    for (const auto& [name, a] : p.attributes())
      if (!name.starts_with("exposedVar:")) attributes.push_back(attributeJson(name, a, findSchemaAttribute(p.type(), name)));
    prim["attributes"] = attributes;
    Json labels = Json::object();
    for (const auto& [taxonomy, values] : p.semantics()) labels[taxonomy] = values;
    prim["semantics"] = labels;
    Json behaviors = Json::array();
    for (const std::string& name : p.behaviors()) {
      const BehaviorSpec* spec = catalog.find(name);
      Json b;
      b["name"] = name;
      b["source"] = loaded_->registry.sourceOf(name);
      b["driven_by"] = spec && spec->eventDriven ? "events" : "timeline";
      Json vars = Json::array();
      if (spec)
        for (const AttributeSpec& var : spec->variables)
          if (const Attribute* a = p.findAttribute(exposedAttributeName(name, var.name)))
            vars.push_back(attributeJson(var.name, *a, &var));
      b["variables"] = vars;
      behaviors.push_back(b);
    }
    prim["behaviors"] = behaviors;
    prims.push_back(prim);
  });
  return Json{{"prims", prims}};
}

Json StudioSession::behaviors() { return Json::parse(describeBehaviorsJson(loaded_->registry)); }

Json StudioSession::edit(const std::string& prim, const std::vector<std::string>& keys, const std::string& jsonValue,
                         bool inAsset) {
  refuseDuringConflict();
  const Prim* target = loaded_->scene.stage.find(prim);
  if (!target) throw StudioError(400, "no prim " + prim);
  std::string yaml;
  try {
    yaml = yamlFlow(jsonValue);
  } catch (const std::exception& e) {
    throw StudioError(400, std::string("the value is not JSON: ") + e.what());
  }
  if (!inAsset) {
    std::string edited;
    try {
      edited = applyTextEdit(text_, TextEdit{prim, keys, yaml});
    } catch (const std::invalid_argument& e) {
      throw StudioError(400, e.what());
    }
    // Checked as a scene: a bad value is refused and the text stays as it was.
    std::unique_ptr<LoadedScene> candidate = check(edited, assetTexts());
    text_ = std::move(edited);
    return adopt(std::move(candidate));
  }
  // In the asset: the file and the prim entry the value is written in.
  const std::string attribute = keys.size() == 3 && keys[0] == "behaviors" ? exposedAttributeName(keys[1], keys[2])
                                                                           : keys.size() == 1 ? keys[0] : std::string();
  const Attribute* a = attribute.empty() ? nullptr : target->findAttribute(attribute);
  if (!a || !a->loc.via)
    throw StudioError(400, prim + ": this value does not come from a smart asset; edit it in the scene");
  const std::string key = assetKey(a->loc.file.str());
  auto it = assetFiles_.find(key);
  if (it == assetFiles_.end()) {
    std::string disk = readText(key);
    it = assetFiles_.emplace(key, AssetFile{disk, disk}).first;
  }
  SceneDocument doc = sceneDocumentFromText(it->second.text, key);
  std::string assetPrim;
  if (const RawNode* prims = doc.root.isMap() ? doc.root.find("prims") : nullptr; prims && prims->isMap())
    for (const RawEntry& e : prims->entries)
      if (e.key.loc.line <= a->loc.line) assetPrim = e.key.scalar;  // the entry the value is written in
  if (assetPrim.empty()) throw StudioError(400, "cannot find the value's prim in " + key);
  std::string edited;
  try {
    edited = applyTextEdit(it->second.text, TextEdit{assetPrim, keys, yaml});
  } catch (const std::invalid_argument& e) {
    throw StudioError(400, e.what());
  }
  std::map<std::string, std::string> texts = assetTexts();
  texts[key] = edited;
  std::unique_ptr<LoadedScene> candidate = check(text_, texts);
  it->second.text = std::move(edited);
  Json result = adopt(std::move(candidate));
  result["asset"] = key;
  return result;
}

Json StudioSession::adopt(std::unique_ptr<LoadedScene> candidate) {
  // Carry what changed over to the stage after the pre-roll; what the
  // pre-roll depends on makes it stale instead.
  const BehaviorCatalog& catalog = candidate->registry.catalog();
  Json changed = Json::array();
  for (const StageChange& c : diffStages(loaded_->scene.stage, candidate->scene.stage)) {
    changed.push_back(Json{{"prim", c.prim}, {"attribute", c.attribute}});
    bool forPreroll = c.attribute == "prim";
    if (c.attribute.starts_with("exposedVar:")) {
      const size_t colon = c.attribute.find(':', 11);
      const BehaviorSpec* spec = catalog.find(c.attribute.substr(11, colon - 11));
      forPreroll = !spec || spec->eventDriven;
    }
    Prim* target = afterPreroll_->find(c.prim);
    if (forPreroll || !target) {
      prerollStale_ = true;
      continue;
    }
    if (auto op = parseXformOpName(c.attribute)) {
      auto it = std::find_if(target->xformOps().begin(), target->xformOps().end(),
                             [&](const XformOp& o) { return o.attributeName() == c.attribute; });
      if (it != target->xformOps().end() && c.value) it->value = *c.value;
      else target->xformOps() = candidate->scene.stage.find(c.prim)->xformOps();
    } else if (c.attribute == "material:binding") {
      target->material() = candidate->scene.stage.find(c.prim)->material();
    } else if (c.value) {
      const Attribute* source = candidate->scene.stage.find(c.prim)->findAttribute(c.attribute);
      target->setAttribute(c.attribute, *c.value, source && source->custom);
    } else {
      target->removeAttribute(c.attribute);
    }
  }
  // Labels are not in the stage diff: carry them over as they are.
  candidate->scene.stage.traverse([&](const Prim& p) {
    if (Prim* target = afterPreroll_->find(p.path()); target && target->semantics() != p.semantics()) {
      target->semantics() = p.semantics();
      changed.push_back(Json{{"prim", p.path()}, {"attribute", "semantics"}});
    }
  });
  loaded_ = std::move(candidate);
  return Json{{"changed", changed}, {"preroll_stale", prerollStale_}, {"unsaved", unsaved()}};
}

std::map<std::string, std::string> StudioSession::assetTexts() const {
  std::map<std::string, std::string> texts;
  for (const auto& [key, file] : assetFiles_) texts[key] = file.text;
  return texts;
}

bool StudioSession::unsaved() const {
  if (text_ != diskText_) return true;
  for (const auto& [key, file] : assetFiles_)
    if (file.text != file.disk) return true;
  return false;
}

std::unique_ptr<LoadedScene> StudioSession::check(const std::string& edited,
                                                  const std::map<std::string, std::string>& assetTexts) {
  SceneRequest request = options_.scene;
  request.sceneText = edited;
  request.assetTexts = assetTexts;
  try {
    return std::make_unique<LoadedScene>(loadSceneForRun(request));
  } catch (const SceneError& e) {
    throw StudioError(400, problemsText(e));
  }
}

void StudioSession::refuseDuringConflict() const {
  if (isUsdStagePath(options_.scene.scenePath))
    throw StudioError(400, options_.scene.scenePath + " is a USD stage: the studio shows it and reloads it when the "
                           "file changes, but edits YAML only; edit the layer, or `sdgbehave flatten` it to a YAML "
                           "scene and open that");
  if (conflict_)
    throw StudioError(409, options_.scene.scenePath + " changed on disk while there are unsaved edits here, so edits "
                           "are refused until you reload it (dropping the edits here) or overwrite it with the edits "
                           "here (Save, after confirming)");
}

Json StudioSession::setAttached(const std::string& prim, const std::string& behavior, bool attach) {
  refuseDuringConflict();
  auto has = [&](const LoadedScene& scene) {
    const Prim* p = scene.scene.stage.find(prim);
    return std::find(p->behaviors().begin(), p->behaviors().end(), behavior) != p->behaviors().end();
  };
  if (!loaded_->scene.stage.find(prim)) throw StudioError(400, "no prim " + prim);
  if (!loaded_->registry.catalog().find(behavior)) throw StudioError(400, "no behavior " + behavior);
  if (has(*loaded_) == attach)
    throw StudioError(400, prim + (attach ? " has " + behavior + " already" : " has no behavior " + behavior));
  // Removing the entry undoes an `enabled: false` (attach) or a local
  // attachment (detach); what a referenced asset brings needs an entry.
  std::string edited = removeTextKey(text_, prim, {"behaviors", behavior});
  std::unique_ptr<LoadedScene> candidate = check(edited, assetTexts());
  if (has(*candidate) != attach) {
    try {
      edited = applyTextEdit(edited, TextEdit{prim, {"behaviors", behavior}, attach ? "{}" : "{enabled: false}"});
    } catch (const std::invalid_argument& e) {
      throw StudioError(400, e.what());
    }
    candidate = check(edited, assetTexts());
  }
  loaded_ = std::move(candidate);
  text_ = std::move(edited);
  runPreroll();
  return Json{{attach ? "attached" : "detached", behavior}, {"unsaved", unsaved()}};
}

void StudioSession::setSeed(int64_t seed) {
  if (seed == seed_) return;
  seed_ = seed;
  prerollStale_ = true;
}

Json StudioSession::preroll() {
  runPreroll();
  return Json{{"settle", settle_}};
}

std::unique_ptr<Stage> StudioSession::stageAt(uint64_t frame, std::optional<Stage>* before) {
  // Each preview replays the frames before it: bound the work one request can ask for.
  constexpr uint64_t kMaxPreviewFrame = 10000;
  if (frame > kMaxPreviewFrame) throw StudioError(400, "frame must be at most " + std::to_string(kMaxPreviewFrame));
  auto stage = std::make_unique<Stage>(*afterPreroll_);
  RunBehaviorSetup setup;
  BehaviorContext context = behaviorContextFor(*loaded_, seed_, setup);
  BehaviorRuntime runtime(*stage, loaded_->registry, context);
  runtime.init();
  // Frame 0's changes include what behaviors do on play, as in `run --record`.
  if (before && frame == 0) before->emplace(*stage);
  runtime.play();
  for (uint64_t f = 0; f <= frame; ++f) {
    if (before && f == frame && frame > 0) before->emplace(*stage);
    runtime.update();
  }
  // The runtime's destroy restores its stage: hand back a copy of the frame.
  auto result = std::make_unique<Stage>(*stage);
  return result;
}

std::vector<uint8_t> StudioSession::preview(uint64_t frame, const std::string& pass, const std::string& camera) {
  const std::optional<PicturePass> picturePass = picturePassNamed(pass);
  if (!picturePass)
    throw StudioError(400, "unknown pass '" + pass + "'; passes: " + text::join(picturePassNames(), ", "));
  std::unique_ptr<Stage> stage = stageAt(frame, nullptr);
  return pictures_.render(*loaded_, *stage, camera, "camera", *picturePass).png;
}

Json StudioSession::record(uint64_t frame) {
  std::optional<Stage> before;
  std::unique_ptr<Stage> after = stageAt(frame, &before);
  Json changes = Json::array();
  for (const StageChange& c : diffStages(*before, *after))
    changes.push_back(Json{{"prim", c.prim}, {"attribute", c.attribute},
                           {"value", c.value ? valueToJson(*c.value) : Json(nullptr)}});
  return Json{{"frame", frame}, {"changes", changes}};
}

Json StudioSession::files(const std::string& kind) const {
  namespace fs = std::filesystem;
  if (kind != "mesh" && kind != "image") throw StudioError(400, "kind is mesh or image, found '" + kind + "'");
  const std::vector<std::string>& extensions = readableExtensions(kind == "mesh" ? FileKind::Mesh : FileKind::Image);
  constexpr size_t kMaxFiles = 2000;
  Json out = Json::array();
  for (const std::string& root : loaded_->assets.roots()) {
    std::error_code ec;
    // Symbolic links are not followed: nothing outside the roots is listed.
    fs::recursive_directory_iterator it(root, fs::directory_options::none, ec), end;
    for (; !ec && it != end && out.size() < kMaxFiles; it.increment(ec)) {
      if (it.depth() > 6) it.disable_recursion_pending();
      if (!it->is_regular_file(ec)) continue;
      std::string ext = it->path().extension().string();
      for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
      if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end()) continue;
      std::string name = it->path().lexically_relative(root).string();
      if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
    }
  }
  return Json{{"kind", kind}, {"files", out}};
}

std::vector<std::string> StudioSession::runFlags() const {
  std::vector<std::string> flags = {"--seed", std::to_string(seed_)};
  const SceneRequest& r = options_.scene;
  for (const std::string& o : r.overrides) flags.insert(flags.end(), {"--set", o});
  for (const std::string& p : r.plugins) flags.insert(flags.end(), {"--plugin", p});
  for (const std::string& s : r.scripts) flags.insert(flags.end(), {"--script", s});
  for (const std::string& a : r.assetRoots) flags.insert(flags.end(), {"--asset-root", a});
  if (!r.isaacAssets.empty()) flags.insert(flags.end(), {"--isaac-assets", r.isaacAssets});
  return flags;
}

FramePlan StudioSession::framePlan(uint64_t frames) const {
  FramePlanFlags flags;
  if (frames) flags.frames = frames;
  return framePlanFor(loaded_->scene, flags, noEnvironment);
}

std::string StudioSession::diff() const {
  const std::string& scene = options_.scene.scenePath;
  std::string out = conflict_ ? lineDiff(diskText_, conflictText_, scene, "as read", "on disk now") +
                                    lineDiff(conflictText_, text_, scene, "on disk now", "edited")
                              : lineDiff(diskText_, text_, scene);
  for (const auto& [key, file] : assetFiles_) out += lineDiff(file.disk, file.text, key);
  return out;
}

Json StudioSession::reload() {
  diskText_ = readText(options_.scene.scenePath);
  diskStamp_ = stampOf(options_.scene.scenePath);
  assetFiles_.clear();
  conflict_ = false;
  conflictText_.clear();
  load(diskText_);
  runPreroll();
  return Json{{"reloaded", options_.scene.scenePath}};
}

Json StudioSession::save(bool overwrite) {
  checkFile();
  if (conflict_ && !overwrite)
    throw StudioError(409, options_.scene.scenePath + " changed on disk after it was read; saving would overwrite "
                           "those changes: reload it (dropping the edits here) or overwrite it (Save, after confirming)");
  // Asset files edited "in the asset" must still be what was read.
  for (const auto& [key, file] : assetFiles_)
    if (!overwrite && file.text != file.disk && readText(key) != file.disk)
      throw StudioError(409, key + " changed on disk after it was read; saving would overwrite those changes: reload "
                                   "(dropping the edits here) or overwrite it (Save, after confirming)");
  Json saved = Json::array();
  if (text_ != diskText_ || conflict_ || assetFiles_.empty()) {
    writeFileAtomic(options_.scene.scenePath, text_);
    saved.push_back(options_.scene.scenePath);
  }
  for (auto& [key, file] : assetFiles_)
    if (file.text != file.disk) {
      writeFileAtomic(key, file.text);
      file.disk = file.text;
      saved.push_back(key);
    }
  diskText_ = text_;
  diskStamp_ = stampOf(options_.scene.scenePath);
  conflict_ = false;
  conflictText_.clear();
  return Json{{"saved", saved}};
}

}  // namespace sdg::studio
