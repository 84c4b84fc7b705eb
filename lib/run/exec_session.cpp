#include "run/exec_session.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>

#include "behavior/runtime.h"
#include "core/diagnostics.h"
#include "core/file_io.h"
#include "core/log.h"
#include "run/dataset_run.h"
#include "scene_io/attached_scripts.h"
#include "scene_io/references.h"
#include "scene_io/scene_loader.h"
#include "scene_io/scene_writer.h"
#include "scene_io/usd_export.h"
#include "scripting/driver_host.h"
#include "scripting/script_context.h"
#include "scripting/script_loader.h"
#include "stage/path.h"
#include "usd/usda_writer.h"

#ifndef SDG_ISAAC_STAND_IN_SOURCE_PATH
#define SDG_ISAAC_STAND_IN_SOURCE_PATH ""
#endif

namespace sdg {
namespace fs = std::filesystem;

namespace {

constexpr const char* kScriptsAttribute = "omni:scripting:scripts";
// What omni.usd's new_stage() makes: Isaac Sim's defaults.
constexpr const char* kNewStageText =
    "version: 1\nstage: {upAxis: Z, metersPerUnit: 1.0, timeCodesPerSecond: 60}\nprims: {}\n";

// The driver's own spec: its context is named "driver" in messages.
const BehaviorSpec& driverSpec() {
  static const BehaviorSpec spec = [] {
    BehaviorSpec s;
    s.name = "driver";
    return s;
  }();
  return spec;
}

std::string absolute(const std::string& path) { return fs::absolute(path).lexically_normal().string(); }

class ExecSession : public scripting::DriverHost {
 public:
  explicit ExecSession(const ExecOptions& options) : options_(options) {
    assetsRoot_ = options.assetsRoot;
    if (assetsRoot_.empty())
      if (const char* env = std::getenv("SDGBEHAVE_ASSETS_ROOT"); env && *env) assetsRoot_ = env;
    if (assetsRoot_.empty()) assetsRoot_ = isaacStandInRoot();
    context_ = std::make_shared<scripting::ScriptContext>();
    context_->driver = true;
    context_->spec = &driverSpec();
    context_->script = options.program;
    newStage();
  }

  ~ExecSession() override {
    try {
      endStage();
    } catch (...) {
    }
  }

  // Writers the program left attached are finished.
  void finishAll(ExecResult& result) {
    for (auto& [id, slot] : writers_) finishWriter(slot);
    writers_.clear();
    for (ExecDataset& d : finished_) result.datasets.push_back(d);
    result.updates = updates_;
  }

  std::shared_ptr<scripting::ScriptContext> context() override { return context_; }

  void newStage() override {
    SceneRequest request;
    request.scenePath = "untitled.usd";
    request.sceneText = kNewStageText;
    request.isaacAssets = assetsRoot_;
    replaceScene(loadSceneForRun(request));
  }

  void openStage(const std::string& path) override {
    SceneRequest request;
    request.scenePath = path;
    request.isaacAssets = assetsRoot_;
    replaceScene(loadSceneForRun(request));
  }

  void saveStage(const std::string& path) override {
    if (path.ends_with(".usda")) {
      UsdExportOptions options;
      options.catalog = &loaded_->registry.catalog();
      usd::Layer layer = exportUsdLayer(loaded_->scene, loaded_->assets, options);
      layer.identifier = path;
      writeFileAtomic(path, usd::writeUsdaLayer(layer));
    } else if (path.ends_with(".yaml") || path.ends_with(".yml")) {
      writeFileAtomic(path, writeSceneYaml(loaded_->scene, loaded_->registry.catalog()));
    } else {
      throw SceneError(SourceLoc{path, 0, 0}, "save_as_stage: expected a file name ending in .usda or .yaml");
    }
  }

  void reference(const std::string& primPath, const std::string& file) override {
    Stage& stage = loaded_->scene.stage;
    Prim* prim = stage.find(primPath);
    if (!prim) throw SceneError(SourceLoc{primPath, 0, 0}, "AddReference: the prim does not exist");
    if (!prim->children().empty())
      throw SceneError(SourceLoc{primPath, 0, 0},
                       "AddReference: only a prim without children can reference a file in sdgbehave's stage");
    // The referencing prim's own transform stays: the file's prim mounts below a
    // fresh prim of the same path, whose ops are put back.
    const std::vector<XformOp> ops = prim->xformOps();
    const SemanticLabels labels = prim->semantics();
    stage.removePrim(primPath);
    AssetLibrary library(buildAssetScene);
    Diagnostics diag;
    ReferenceSpec spec;
    spec.file = file;
    spec.loc = SourceLoc{primPath, 0, 0};
    library.mount(spec, fs::current_path().string(), primPath, stage, loaded_->registry.catalog(), diag);
    diag.throwIfErrors();
    Prim* mounted = stage.find(primPath);
    if (!mounted) throw SceneError(spec.loc, "AddReference: " + file + " has no prim to reference");
    for (const XformOp& op : ops) mounted->xformOps().push_back(op);
    for (const auto& [type, values] : labels) mounted->semantics()[type] = values;
    // Behaviors the file's prims carry start now, as a stage's do when it opens.
    for (Prim* p : stage.subtree(*mounted)) {
      rememberListedScripts(*p);
      for (const std::string& name : p->behaviors()) runtime_->attach(*p, name);
    }
  }

  void movePrim(const std::string& from, const std::string& to) override {
    Stage& stage = loaded_->scene.stage;
    const SourceLoc at{from, 0, 0};
    Prim* source = stage.find(from);
    if (!source || source->isPseudoRoot()) throw SceneError(at, "MovePrim: the prim does not exist");
    if (std::string why = path::whyInvalid(to); !why.empty()) throw SceneError(SourceLoc{to, 0, 0}, "MovePrim: " + why);
    if (stage.find(to)) throw SceneError(SourceLoc{to, 0, 0}, "MovePrim: a prim exists at the new path already");
    if (to.starts_with(from + "/")) throw SceneError(at, "MovePrim: a prim cannot move below itself");
    if (!stage.find(path::parent(to))) throw SceneError(SourceLoc{to, 0, 0}, "MovePrim: the new parent does not exist");
    const std::vector<Prim*> subtree = stage.subtree(*source);
    for (const Prim* p : subtree)
      if (!p->behaviors().empty())
        throw SceneError(SourceLoc{p->path(), 0, 0}, "MovePrim: the prim has behaviors running; sdgbehave moves "
                                                     "prims without behaviors only");
    auto moved = [&](const std::string& path) {
      return path == from ? to : path.starts_with(from + "/") ? to + path.substr(from.size()) : path;
    };
    for (const Prim* p : subtree) {  // pre-order: parents first
      Prim& copy = stage.definePrim(moved(p->path()), p->type());
      for (const auto& [name, attribute] : p->attributes()) copy.setAttribute(name, attribute.value, attribute.custom);
      copy.xformOps() = p->xformOps();
      copy.semantics() = p->semantics();
      copy.material() = p->material();
      copy.metadata() = p->metadata();
    }
    stage.removePrim(from);
    stage.traverse([&](Prim& p) {
      if (p.material()) p.material()->path = moved(p.material()->path);
    });
    if (auto it = listed_.find(from); it != listed_.end()) {
      listed_[to] = it->second;
      listed_.erase(it);
    }
  }

  std::string assetsRoot() const override { return assetsRoot_; }

  void update() override {
    attachListedScripts();
    runtime_->update();
    ++updates_;
  }
  void play() override { runtime_->play(); }
  void pause() override { runtime_->pause(); }
  void stop() override { runtime_->stop(); }
  bool playing() const override { return runtime_->timeline().playing(); }
  double time() const override { return runtime_->timeline().time(); }
  double timeCodesPerSecond() const override { return loaded_->scene.stage.metadata().timeCodesPerSecond; }
  void setSeed(int64_t seed) override { seed_ = seed; }

  int attachWriter(const std::string& outDir, const nlohmann::json& options, const std::vector<std::string>& cameras,
                   int width, int height) override {
    for (const auto& [id, slot] : writers_)
      if (absolute(slot.folder) == absolute(outDir))
        throw SceneError(SourceLoc{outDir, 0, 0}, "another attached writer writes into this folder");
    for (const std::string& camera : cameras) {
      const Prim* p = loaded_->scene.stage.find(camera);
      if (!p || p->type() != PrimType::Camera)
        throw SceneError(SourceLoc{camera, 0, 0}, "render product: the stage has no Camera prim at this path");
    }
    // The writer's section is read, checked and located as a scene's is.
    SceneRequest request;
    request.scenePath = "writer.initialize()";
    request.sceneText = "version: 1\nwriter: " + options.dump() + "\nprims: {}\n";
    WriterSlot slot;
    slot.folder = outDir;
    slot.loaded = std::make_unique<LoadedScene>(loadSceneForRun(request));
    LoadedScene& w = *slot.loaded;
    w.scene.sourcePath = absolute(options_.program);
    w.scene.capture.set("cameras", Value::makeStringArray(cameras));
    w.scene.capture.set("contact_sheet", Value::makeBool(false));  // Isaac's writers make none
    w.assets = loaded_->assets;
    w.scriptFiles = loaded_->scriptFiles;
    w.scene.stage = loaded_->scene.stage;  // what a BOP writer's models are read from
    DatasetRunOptions run;
    run.seed = seed_;
    run.outDir = outDir;
    run.overwrite = true;  // as Isaac's writers do, files of an earlier run are replaced
    run.threads = options_.threads;
    run.render = options_.render;
    run.render.width = width;
    run.render.height = height;
    slot.capture = std::make_unique<DatasetCapture>(w, run);
    const int id = nextWriter_++;
    writers_.emplace(id, std::move(slot));
    return id;
  }

  void capture() override {
    for (auto& [id, slot] : writers_) {
      // The live stage is lent to the writer's scene for the capture (a move,
      // not a copy); what the frame needs is read before it returns.
      Stage& live = loaded_->scene.stage;
      Stage& lent = slot.loaded->scene.stage;
      std::swap(live, lent);
      try {
        slot.capture->capture();
      } catch (...) {
        std::swap(live, lent);
        throw;
      }
      std::swap(live, lent);
    }
  }

  void detachWriter(int id) override {
    auto it = writers_.find(id);
    if (it == writers_.end()) return;
    finishWriter(it->second);
    writers_.erase(it);
  }

  size_t attachedWriters() const override { return writers_.size(); }

 private:
  struct WriterSlot {
    std::string folder;
    std::unique_ptr<LoadedScene> loaded;
    std::unique_ptr<DatasetCapture> capture;
  };

  void finishWriter(WriterSlot& slot) {
    DatasetRunResult r = slot.capture->finish();
    finished_.push_back(ExecDataset{slot.folder, r.frames, r.files});
    log::info(slot.folder + ": " + std::to_string(r.frames) + " frame(s), " + std::to_string(r.files) + " files");
  }

  // Ends the behaviors of the open stage (on_stop, on_destroy).
  void endStage() {
    if (runtime_) runtime_->destroy();
    runtime_.reset();
  }

  void replaceScene(LoadedScene loaded) {
    endStage();
    loaded_ = std::make_unique<LoadedScene>(std::move(loaded));
    context_->stage = &loaded_->scene.stage;
    context_->assets = &loaded_->assets;
    setup_ = std::make_unique<RunBehaviorSetup>();
    runtime_ = std::make_unique<BehaviorRuntime>(loaded_->scene.stage, loaded_->registry,
                                                 behaviorContextFor(*loaded_, seed_, *setup_));
    context_->events = &runtime_->events();
    listed_.clear();
    loaded_->scene.stage.traverse([this](Prim& p) { rememberListedScripts(p); });
    runtime_->init();
  }

  static std::vector<std::string> listedScripts(const Prim& prim) {
    const Value* v = prim.value(kScriptsAttribute);
    if (!v || v->type() != ValueType::AssetArray) return {};
    return v->get<std::vector<std::string>>();
  }

  void rememberListedScripts(const Prim& prim) {
    std::vector<std::string> files = listedScripts(prim);
    if (!files.empty()) listed_[prim.path()] = std::move(files);
  }

  // Isaac's script manager starts the behaviors of a script as soon as a
  // prim lists it: so does every update here, for files listed since the
  // last (a file that exists is loaded; a missing one of Isaac's six is its
  // built-in, as when a scene lists it).
  void attachListedScripts() {
    std::vector<std::pair<std::string, std::string>> added;  // (prim, file)
    loaded_->scene.stage.traverse([&](const Prim& p) {
      std::vector<std::string> files = listedScripts(p);
      if (files.empty()) return;
      std::vector<std::string>& known = listed_[p.path()];
      for (const std::string& f : files)
        if (std::find(known.begin(), known.end(), f) == known.end()) added.emplace_back(p.path(), f);
      known = files;
    });
    for (const auto& [primPath, file] : added) {
      const SourceLoc where{primPath + "." + kScriptsAttribute, 0, 0};
      BehaviorRegistry& registry = loaded_->registry;
      AttachedScript a = resolveAttachedScript(
          file, IsaacScriptChoice::Auto,
          [&registry](const std::string& f, const SourceLoc& loc) { return scripting::loadScript(registry, f, loc); },
          where);
      if (!a.error.empty()) throw SceneError(where, a.error);
      if (a.builtinStandIn) log::debug(primPath + ": " + file + " runs as the built-in " + a.behaviors.front());
      Prim* prim = loaded_->scene.stage.find(primPath);
      for (const std::string& name : a.behaviors) {
        if (std::find(prim->behaviors().begin(), prim->behaviors().end(), name) != prim->behaviors().end()) continue;
        prim->behaviors().push_back(name);
        runtime_->attach(*prim, name);
      }
    }
  }

  ExecOptions options_;
  std::string assetsRoot_;
  int64_t seed_ = 0;
  std::unique_ptr<LoadedScene> loaded_;
  std::unique_ptr<RunBehaviorSetup> setup_;
  std::unique_ptr<BehaviorRuntime> runtime_;
  std::shared_ptr<scripting::ScriptContext> context_;
  std::map<std::string, std::vector<std::string>> listed_;  // prim -> files it listed at the last update
  std::map<int, WriterSlot> writers_;
  int nextWriter_ = 1;
  std::vector<ExecDataset> finished_;
  uint64_t updates_ = 0;
};

// Sets the program's working folder for the run and puts the old one back.
class WorkingFolder {
 public:
  explicit WorkingFolder(const std::string& dir) {
    if (dir.empty()) return;
    previous_ = fs::current_path();
    std::error_code ec;
    fs::create_directories(dir, ec);
    fs::current_path(dir, ec);
    if (ec) throw SceneError(SourceLoc{"--out-root", 0, 0}, "cannot work in " + dir + ": " + ec.message());
  }
  ~WorkingFolder() {
    std::error_code ec;
    if (!previous_.empty()) fs::current_path(previous_, ec);
  }

 private:
  fs::path previous_;
};

}  // namespace

std::string isaacStandInRoot() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / "share" / "sdgbehave" / "scenes" / "isaac-stand-in";
    if (fs::is_directory(installed, ec)) return installed.string();
  }
  return SDG_ISAAC_STAND_IN_SOURCE_PATH;
}

ExecResult runExec(const ExecOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::error_code ec;
  if (!fs::is_regular_file(options.program, ec))
    throw SceneError(SourceLoc{options.program, 0, 0}, "the program does not exist (expected a Python file)");
  ExecOptions resolved = options;
  resolved.program = absolute(options.program);
  if (!resolved.assetsRoot.empty()) resolved.assetsRoot = absolute(resolved.assetsRoot);
  WorkingFolder folder(options.outRoot);
  ExecSession session(resolved);
  scripting::setDriverHost(&session);
  ExecResult result;
  try {
    scripting::runDriverProgram(resolved.program, options.program, options.args);
  } catch (...) {
    scripting::setDriverHost(nullptr);
    try {
      session.finishAll(result);  // the frames written so far stay a dataset
    } catch (const std::exception& e) {
      log::warn(std::string("while finishing the writers after the failure: ") + e.what());
    }
    throw;
  }
  scripting::setDriverHost(nullptr);
  session.finishAll(result);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace sdg
