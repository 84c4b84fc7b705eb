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
  for (size_t i = 0; i < scripts.size(); ++i)
    scripting::loadScript(registry, scripts[i], SourceLoc{"--script[" + std::to_string(i + 1) + "]", 0, 0});
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

// A file the scene declares, relative to its folder; SceneError at the
// declaration when it does not exist.
std::string existingDeclaredFile(const std::filesystem::path& sceneDir, const DeclaredFile& file, const char* what) {
  std::filesystem::path p(file.path);
  if (p.is_relative()) p = sceneDir / p;
  p = p.lexically_normal();
  std::error_code ec;
  if (std::filesystem::is_directory(p, ec))
    throw SceneError(file.loc, std::string(what) + " " + text::quote(file.path) + " is a folder, not a file: " + p.string());
  if (!std::filesystem::is_regular_file(p, ec))
    throw SceneError(file.loc, std::string(what) + " " + text::quote(file.path) + " not found; searched: " + p.string());
  return p.string();
}

// omni:scripting:scripts (scene_io/attached_scripts.h): --isaac-scripts,
// else the scene's run.isaac_scripts, else auto.
IsaacScriptChoice isaacScriptChoice(const SceneRequest& request, std::optional<IsaacScriptChoice> setting) {
  if (request.isaacScripts.empty()) return setting.value_or(IsaacScriptChoice::Auto);
  if (auto choice = parseIsaacScriptChoice(request.isaacScripts)) return *choice;
  throw SceneError(SourceLoc{"--isaac-scripts", 0, 0}, "expected one of " + std::string(kIsaacScriptChoices) +
                                                           ", found " + text::quote(request.isaacScripts));
}

// Loads the behavior scripts prims list in omni:scripting:scripts and
// records what each file stands for; says once per run which built-ins
// stand in for missing Isaac files.
class ScriptAttacher {
 public:
  ScriptAttacher(BehaviorRegistry& registry, IsaacScriptChoice choice) : registry_(registry), choice_(choice) {}

  // The behaviors `path` stands for; SceneError at `where` when it cannot.
  std::vector<std::string> attach(const std::string& path, const SourceLoc& where) {
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
  const std::vector<std::string>& scriptFiles() const { return scriptFiles_; }

 private:
  BehaviorRegistry& registry_;
  IsaacScriptChoice choice_;
  std::vector<std::string> scriptFiles_;  // files loaded (not the built-ins standing in)
  std::vector<std::string> missing_;
};

}  // namespace

bool isUsdStagePath(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".usd" || ext == ".usda" || ext == ".usdc" || ext == ".usdz";
}

namespace {

// A USD stage given where a scene is expected: its prims imported
// (scene_io/usd_import.h), the defaults it does not say added, then --set
// and the checks every scene gets.
LoadedScene loadUsdStageForRun(const SceneRequest& request) {
  BehaviorRegistry registry = registryWithPlugins(request.plugins, request.scripts);
  UsdImportReport report;
  UsdImportOptions options = usdImportOptionsFor(request.overrides);
  options.registerScript = [&](const std::string& script) {
    scripting::loadScript(registry, script, SourceLoc{request.scenePath, 0, 0});
  };
  // Scripts the prims list load as the import meets them (before their
  // prim's exposedVar values are read against the script's variables).
  ScriptAttacher attacher(registry, isaacScriptChoice(request, std::nullopt));
  options.attachScript = [&attacher](const std::string& path, const SourceLoc& where) {
    return attacher.attach(path, where);
  };
  Scene scene = importUsdScene(request.scenePath, registry.catalog(), options, report);
  for (const std::string& w : report.warnings) log::debug(w);  // each place a loss summary counts
  for (const std::string& script : report.scriptFiles) scripting::loadScript(registry, script, SourceLoc{request.scenePath, 0, 0});
  attacher.sayNote();
  Diagnostics diag;
  applyOverrides(request.overrides, registry.catalog(), scene, diag);
  applyRenderSettingsToStage(scene);
  if (!diag.hasErrors()) validateScene(scene, registry.catalog(), diag);
  diag.throwIfErrors();
  scripting::setHookTimeout(request.hookTimeout.value_or(scene.run.get("hook_timeout").get<double>()));
  AssetResolver assets =
      makeSceneResolver(scene.sourceDir, scene.assetRoots, request.assetRoots, isaacRootFor(request, scene));
  if (request.confineAssets) assets.confineToRoots();
  checkStageFiles(scene.stage, registry.catalog(), assets, diag);
  diag.throwIfErrors();
  std::vector<std::string> scriptFiles = request.scripts;
  for (const std::string& s : report.scriptFiles) scriptFiles.push_back(s);
  for (const std::string& s : attacher.scriptFiles()) scriptFiles.push_back(s);
  for (std::string& file : scriptFiles) file = std::filesystem::absolute(file).lexically_normal().string();
  // Every layer read is part of the run's identity; package entries by their package.
  std::vector<std::string> mounted;
  for (const std::string& layer : report.layers) {
    std::string file = std::filesystem::absolute(usd::splitPackagePath(layer).first).lexically_normal().string();
    if (std::find(mounted.begin(), mounted.end(), file) == mounted.end()) mounted.push_back(file);
  }
  std::vector<std::string> pluginFiles = request.plugins;
  for (std::string& file : pluginFiles) file = std::filesystem::absolute(file).lexically_normal().string();
  return LoadedScene{std::move(registry),    std::move(scene),      std::move(assets),
                     std::move(scriptFiles), std::move(mounted),    std::move(pluginFiles),
                     report.losses.warnings()};
}

}  // namespace

LoadedScene loadSceneForRun(const SceneRequest& request) {
  if (isUsdStagePath(request.scenePath) && !request.sceneText) return loadUsdStageForRun(request);
  SceneDocument doc = request.sceneText ? sceneDocumentFromText(*request.sceneText, request.scenePath)
                                        : readSceneDocument(request.scenePath);
  BehaviorRegistry registry = registryWithPlugins(request.plugins, request.scripts);
  // The scene's own plugins and scripts load before its prims are read:
  // their behaviors must be known to check the prims. Paths are relative to
  // the scene file.
  const std::filesystem::path sceneDir = std::filesystem::path(request.scenePath).parent_path();
  std::vector<std::string> scriptFiles = request.scripts;
  for (const DeclaredFile& script : declaredFiles(doc, "scripts")) {
    scriptFiles.push_back(existingDeclaredFile(sceneDir, script, "scripts: behavior script"));
    scripting::loadScript(registry, scriptFiles.back(), script.loc);
  }
  std::vector<std::string> pluginFiles = request.plugins;
  for (const DeclaredFile& plugin : declaredFiles(doc, "plugins")) {
    pluginFiles.push_back(existingDeclaredFile(sceneDir, plugin, "plugins: plugin library"));
    registry.loadPlugin(pluginFiles.back(), plugin.loc);
  }
  for (std::string& file : pluginFiles) file = std::filesystem::absolute(file).lexically_normal().string();
  // Script files prims list in omni:scripting:scripts, as Isaac attaches them.
  ScriptAttacher attacher(registry, isaacScriptChoice(request, isaacScriptSetting(doc.root)));
  for (const ListedScript& listed : listedScriptFiles(doc.root)) attacher.attach(listed.path, listed.loc);
  for (const std::string& file : attacher.scriptFiles()) scriptFiles.push_back(file);
  attacher.sayNote();
  // Smart assets: their scripts register before any prim is read, so that
  // the scene can attach and override their behaviors.
  AssetLibrary assetLibrary(buildAssetScene, request.assetTexts);
  for (const DeclaredFile& script : assetLibrary.preload(doc)) {
    scriptFiles.push_back(script.path);
    scripting::loadScript(registry, script.path, script.loc);
  }
  Scene scene = buildScene(doc, registry.catalog(), request.overrides, &assetLibrary);
  scripting::setHookTimeout(request.hookTimeout.value_or(scene.run.get("hook_timeout").get<double>()));
  AssetResolver assets =
      makeSceneResolver(scene.sourceDir, scene.assetRoots, request.assetRoots, isaacRootFor(request, scene));
  if (request.confineAssets) assets.confineToRoots();
  Diagnostics diag;
  checkStageFiles(scene.stage, registry.catalog(), assets, diag);
  diag.throwIfErrors();
  for (std::string& file : scriptFiles) file = std::filesystem::absolute(file).lexically_normal().string();
  std::vector<std::string> unique;
  for (std::string& file : scriptFiles)
    if (std::find(unique.begin(), unique.end(), file) == unique.end()) unique.push_back(std::move(file));
  scriptFiles = std::move(unique);
  return LoadedScene{std::move(registry),    std::move(scene),     std::move(assets),
                     std::move(scriptFiles), assetLibrary.files(), std::move(pluginFiles),
                     assetLibrary.usdLosses().warnings()};
}

void reloadBehaviorScript(const std::string& path) { scripting::reloadScript(path); }

}  // namespace sdg
