#include "run/scene_setup.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "assets/file_check.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "scripting/hook_watchdog.h"
#include "scripting/script_loader.h"
#include "core/log.h"
#include "core/text.h"
#include "core/file_io.h"
#include "scene_io/attached_scripts.h"
#include "run/color_renderer_choice.h"
#include "scene_io/references.h"
#include "scene_io/scene_loader.h"
#include "scene_io/scene_source.h"
#include "scene_io/overrides.h"
#include "scene_io/scene_validate.h"
#include "scene_io/scene_writer.h"
#include "scene_io/usd_import.h"
#include "usd/layer_io.h"

namespace sdg {

BehaviorRegistry registryWithPlugins(const std::vector<std::string>& plugins, const std::vector<std::string>& scripts) {
  BehaviorRegistry registry = builtinRegistry();
  for (size_t i = 0; i < plugins.size(); ++i)
    registry.loadPlugin(plugins[i], SourceLoc{"--plugin[" + std::to_string(i + 1) + "]", 0, 0});
  Diagnostics failed;  // every --script that does not load, not only the first
  for (size_t i = 0; i < scripts.size(); ++i) try {
      scripting::loadScript(registry, scripts[i], SourceLoc{"--script[" + std::to_string(i + 1) + "]", 0, 0});
    } catch (const SceneError& e) {
      for (const Diagnostic& d : e.problems()) failed.error(d.loc, d.message);
    }
  failed.throwIfErrors();
  return registry;
}

RenderSettings renderSettingsFor(const Scene& scene, const RenderOverrides& overrides) {
  RenderSettings settings;
  const Vec2i resolution = scene.render.get("resolution").get<Vec2i>();
  settings.width = overrides.width.value_or(resolution.x());
  settings.height = overrides.height.value_or(resolution.y());
  settings.subframes = overrides.subframes.value_or(int(scene.render.getUInt("subframes")));
  const std::string mode = overrides.mode.value_or(scene.render.getString("mode"));
  settings.mode = mode == "pathtraced" ? RenderMode::PathTraced : RenderMode::Raster;
  const std::string tracer = scene.render.getString("pathtracer");
  settings.pathTracer = tracer == "cpu"   ? PathTracerChoice::Cpu
                        : tracer == "gpu" ? PathTracerChoice::Gpu
                                          : PathTracerChoice::Auto;
  // Said before any output exists (run/color_renderer_choice.cpp says it again where the renderer is made).
  if (settings.mode == RenderMode::PathTraced && settings.pathTracer == PathTracerChoice::Gpu && !gpuPathTracerBuiltIn()) {
    const SourceLoc* at = scene.render.locOf("pathtracer");
    throw SceneError(at ? *at : SourceLoc{scene.sourcePath, 0, 0}, kNoGpuTracer);
  }
  settings.samples = overrides.samples.value_or(int(scene.render.getUInt("samples")));
  settings.maxBounces = int(scene.render.getUInt("max_bounces"));
  settings.denoise = overrides.denoise.value_or(scene.render.getBool("denoise"));
  settings.gpu = overrides.gpu;
  return settings;
}

RenderSettings defaultRenderSettings() { return renderSettingsFor(Scene(), RenderOverrides{}); }

std::unique_ptr<GlContext> glContextFor(const Scene& scene, const RenderOverrides& overrides) {
  return createGlContext(overrides.backend.value_or(scene.render.getString("backend")), overrides.gpu);
}

PhysicsSettings physicsSettingsFor(const Scene& scene) {
  const OptionSet& o = scene.physics;
  PhysicsSettings s;
  s.gravity = o.get("gravity").get<double>();
  s.density = o.get("density").get<double>();
  s.solverIterations = o.getUInt("solver_iterations");
  s.settleLinearSpeed = o.get("settle_linear_speed").get<double>();
  s.settleAngularSpeed = o.get("settle_angular_speed").get<double>();
  s.maxSettleSteps = o.getUInt("max_settle_steps");
  s.requireSettled = o.get("require_settled").get<bool>();
  return s;
}

BehaviorContext behaviorContextFor(LoadedScene& loaded, int64_t seed, RunBehaviorSetup& setup) {
  setup.physics = physicsSettingsFor(loaded.scene);
  BehaviorContext context;
  context.assets = &loaded.assets;
  context.runSeed = seed;
  context.physics = &setup.physics;
  context.hooks.report = [&setup](const std::string&, const nlohmann::ordered_json& report) {
    setup.reports.push_back(report);
  };
  return context;
}

Scene flattenedScene(const LoadedScene& loaded) {
  Scene saved = loaded.scene;
  // Absolute roots, scripts and plugins, so the file works from any folder.
  saved.assetRoots.clear();
  for (const std::string& root : loaded.assets.roots())
    saved.assetRoots.push_back(std::filesystem::absolute(root).lexically_normal().string());
  if (!loaded.assets.isaacRoot().empty())
    saved.isaacAssets = std::filesystem::absolute(loaded.assets.isaacRoot()).lexically_normal().string();
  // Every script, the referenced assets' too: the saved stage is flat.
  saved.scripts = loaded.scriptFiles;
  for (std::string& plugin : saved.plugins)
    if (std::filesystem::path(plugin).is_relative())
      plugin = std::filesystem::absolute(std::filesystem::path(loaded.scene.sourceDir) / plugin).lexically_normal().string();
  return saved;
}

void saveStageAfterPreroll(const LoadedScene& loaded, const std::string& path) {
  Scene saved = flattenedScene(loaded);
  saved.events.clear();
  writeFileAtomic(path, writeSceneYaml(saved, loaded.registry.catalog()));
}

namespace {

// --isaac-assets, else SDGBEHAVE_ISAAC_ASSETS, else the scene's isaac_assets
// (relative to the scene): the machine's setting beats the shared file's.
// A root that is not a folder is an error where it was given.
std::string isaacRootFor(const SceneRequest& request, const Scene& scene) {
  namespace fs = std::filesystem;
  std::string root;
  SourceLoc where;
  if (!request.isaacAssets.empty()) {
    root = request.isaacAssets;
    where = SourceLoc{"--isaac-assets", 0, 0};
  } else if (const char* env = std::getenv("SDGBEHAVE_ISAAC_ASSETS"); env && *env) {
    root = env;
    where = SourceLoc{"SDGBEHAVE_ISAAC_ASSETS", 0, 0};
  } else if (!scene.isaacAssets.empty()) {
    fs::path p(scene.isaacAssets);
    root = (p.is_relative() ? fs::path(scene.sourceDir) / p : p).lexically_normal().string();
    where = scene.isaacAssetsLoc;
  }
  std::error_code ec;
  if (!root.empty() && !fs::is_directory(root, ec))
    throw SceneError(where, "Isaac Sim asset root " + text::quote(root) + " is not a folder");
  return root;
}

// omni:scripting:scripts (scene_io/attached_scripts.h): --isaac-scripts,
// else the scene's run.isaac_scripts, else auto.
IsaacScriptChoice isaacScriptChoice(const SceneRequest& request, std::optional<IsaacScriptChoice> setting) {
  if (request.isaacScripts.empty()) return setting.value_or(IsaacScriptChoice::Auto);
  if (auto choice = parseIsaacScriptChoice(request.isaacScripts)) return *choice;
  throw SceneError(SourceLoc{"--isaac-scripts", 0, 0}, "expected one of " + std::string(kIsaacScriptChoices) +
                                                           ", found " + text::quote(request.isaacScripts));
}

// What reading a scene needs from the run (scene_io/scene_source.h): the
// behavior registry, scripts run by the embedded interpreter, plugin
// libraries; files listed in omni:scripting:scripts are attached as Isaac
// attaches them, recorded in the catalog, and the built-ins standing in
// for missing Isaac files are said once per run.
class RunScriptHost : public SceneScriptHost {
 public:
  RunScriptHost(BehaviorRegistry& registry, const SceneRequest& request) : registry_(registry), request_(request) {}

  const BehaviorCatalog& catalog() const override { return registry_.catalog(); }
  void loadScript(const std::string& path, const SourceLoc& where) override {
    scripting::loadScript(registry_, path, where);
  }
  void loadPlugin(const std::string& path, const SourceLoc& where) override { registry_.loadPlugin(path, where); }
  void sceneIsaacScripts(std::optional<IsaacScriptChoice> setting) override {
    choice_ = isaacScriptChoice(request_, setting);
  }
  std::vector<std::string> attach(const std::string& path, const SourceLoc& where) override {
    if (auto known = registry_.catalog().attachedScripts.find(path); known != registry_.catalog().attachedScripts.end())
      return known->second;
    AttachedScript a = resolveAttachedScript(path, choice_, [this](const std::string& file, const SourceLoc& loc) {
      scriptFiles_.push_back(file);
      return scripting::loadScript(registry_, file, loc);
    }, where);
    if (!a.error.empty()) throw SceneError(where, "omni:scripting:scripts: " + a.error);
    if (a.builtinStandIn) missing_.push_back(path);
    registry_.attachScriptFile(path, a.behaviors);
    return a.behaviors;
  }

  void sayNote() const {
    if (!missing_.empty()) log::info(builtinStandInNote(missing_));
  }
  // Files attached that ran (not the built-ins standing in), in load order.
  const std::vector<std::string>& scriptFiles() const { return scriptFiles_; }

 private:
  BehaviorRegistry& registry_;
  const SceneRequest& request_;
  IsaacScriptChoice choice_ = IsaacScriptChoice::Auto;
  std::vector<std::string> scriptFiles_;
  std::vector<std::string> missing_;
};

std::string absoluteNormal(const std::string& path) {
  return std::filesystem::absolute(path).lexically_normal().string();
}

// Each once, in order.
std::vector<std::string> uniqueFiles(std::vector<std::string> files) {
  std::vector<std::string> unique;
  for (std::string& file : files)
    if (std::find(unique.begin(), unique.end(), file) == unique.end()) unique.push_back(std::move(file));
  return unique;
}

}  // namespace

LoadedScene loadSceneForRun(const SceneRequest& request) {
  BehaviorRegistry registry = registryWithPlugins(request.plugins, request.scripts);
  RunScriptHost host(registry, request);
  SceneSourceRead read = readSceneSource(
      SceneSource{request.scenePath, request.sceneText, request.overrides, request.assetTexts}, host);
  host.sayNote();
  Scene& scene = read.scene;
  // A USD stage's scripts are the files its prims list that ran.
  if (isUsdStagePath(request.scenePath) && !request.sceneText)
    for (const std::string& file : host.scriptFiles())
      if (std::find(scene.scripts.begin(), scene.scripts.end(), file) == scene.scripts.end()) scene.scripts.push_back(file);
  scripting::setHookTimeout(request.hookTimeout.value_or(scene.run.get("hook_timeout").get<double>()));
  AssetResolver assets =
      makeSceneResolver(scene.sourceDir, scene.assetRoots, request.assetRoots, isaacRootFor(request, scene));
  if (request.confineAssets) assets.confineToRoots();
  Diagnostics diag;
  checkStageFiles(scene.stage, registry.catalog(), assets, diag);
  diag.throwIfErrors();
  // What the run's identity hashes: every script and plugin it loaded, every file it mounted.
  std::vector<std::string> scriptFiles = request.scripts;
  scriptFiles.insert(scriptFiles.end(), read.scriptFiles.begin(), read.scriptFiles.end());
  scriptFiles.insert(scriptFiles.end(), host.scriptFiles().begin(), host.scriptFiles().end());
  for (std::string& file : scriptFiles) file = absoluteNormal(file);
  std::vector<std::string> pluginFiles = request.plugins;
  pluginFiles.insert(pluginFiles.end(), read.pluginFiles.begin(), read.pluginFiles.end());
  for (std::string& file : pluginFiles) file = absoluteNormal(file);
  return LoadedScene{std::move(registry),
                     std::move(read.scene),
                     std::move(assets),
                     uniqueFiles(std::move(scriptFiles)),
                     std::move(read.mountedFiles),
                     std::move(pluginFiles),
                     std::move(read.dropped)};
}

void reloadBehaviorScript(const std::string& path) { scripting::reloadScript(path); }

}  // namespace sdg
