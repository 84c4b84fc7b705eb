#include "scene_io/scene_source.h"

#include <algorithm>
#include <filesystem>
#include <functional>

#include "core/log.h"
#include "core/text.h"
#include "scene_io/overrides.h"
#include "scene_io/references.h"
#include "scene_io/scene_loader.h"
#include "scene_io/scene_validate.h"
#include "scene_io/usd_import.h"
#include "usd/layer_io.h"

namespace sdg {
namespace {

namespace fs = std::filesystem;

std::string absoluteNormal(const std::string& path) { return fs::absolute(path).lexically_normal().string(); }

void addOnce(std::vector<std::string>& list, std::string item) {
  if (std::find(list.begin(), list.end(), item) == list.end()) list.push_back(std::move(item));
}

// A file the scene declares, relative to its folder; SceneError at the
// declaration when it does not exist.
std::string existingDeclaredFile(const fs::path& sceneDir, const DeclaredFile& file, const char* what) {
  fs::path p(file.path);
  if (p.is_relative()) p = sceneDir / p;
  p = p.lexically_normal();
  std::error_code ec;
  if (fs::is_directory(p, ec))
    throw SceneError(file.loc, std::string(what) + " " + text::quote(file.path) + " is a folder, not a file: " + p.string());
  if (!fs::is_regular_file(p, ec))
    throw SceneError(file.loc, std::string(what) + " " + text::quote(file.path) + " not found; searched: " + p.string());
  return p.string();
}

// A USD stage: its prims imported (usd_import.h), the defaults it does not
// say added, then --set and the checks every scene gets. The files its
// prims list in omni:scripting:scripts are attached as the import meets
// them, before their exposedVar values are read against the behaviors.
SceneSourceRead readUsdStage(const SceneSource& source, SceneScriptHost& host) {
  UsdImportReport report;
  UsdImportOptions options = usdImportOptionsFor(source.overrides);
  host.sceneIsaacScripts(std::nullopt);
  options.attachScript = [&host](const std::string& path, const SourceLoc& where) { return host.attach(path, where); };
  SceneSourceRead read;
  read.scene = importUsdScene(source.path, host.catalog(), options, report);
  for (const std::string& w : report.warnings) log::debug(w);  // each place a loss summary counts
  Diagnostics diag;
  applyOverrides(source.overrides, host.catalog(), read.scene, diag);
  applyRenderSettingsToStage(read.scene);
  if (!diag.hasErrors()) validateScene(read.scene, host.catalog(), diag);
  diag.throwIfErrors();
  // Every layer read is part of the run's identity; package entries by their package.
  for (const std::string& layer : report.layers) addOnce(read.mountedFiles, absoluteNormal(usd::splitPackagePath(layer).first));
  read.dropped = report.losses.warnings();
  return read;
}

// A YAML scene: its own plugins and scripts load before its prims are read
// (their behaviors must be known to check the prims; paths relative to the
// scene file), then the files its prims list, then its smart assets'
// scripts and the files the USD stages it mounts list.
SceneSourceRead readYamlScene(const SceneSource& source, SceneScriptHost& host) {
  SceneDocument doc = source.text ? sceneDocumentFromText(*source.text, source.path) : readSceneDocument(source.path);
  SceneSourceRead read;
  const fs::path sceneDir = fs::path(source.path).parent_path();
  // Every script is tried before giving up, so that one run of validate
  // names every script that does not load (prims cannot be read without
  // their behaviors, so loading stops after the scripts).
  Diagnostics failed;
  auto attempt = [&failed](const std::function<void()>& load) {
    try {
      load();
    } catch (const SceneError& e) {
      for (const Diagnostic& d : e.problems()) failed.error(d.loc, d.message);
    }
  };
  for (const DeclaredFile& script : declaredFiles(doc, "scripts"))
    attempt([&] {
      read.scriptFiles.push_back(existingDeclaredFile(sceneDir, script, "scripts: behavior script"));
      host.loadScript(read.scriptFiles.back(), script.loc);
    });
  for (const DeclaredFile& plugin : declaredFiles(doc, "plugins"))
    attempt([&] {
      read.pluginFiles.push_back(existingDeclaredFile(sceneDir, plugin, "plugins: plugin library"));
      host.loadPlugin(read.pluginFiles.back(), plugin.loc);
    });
  host.sceneIsaacScripts(isaacScriptSetting(doc.root));
  for (const ListedScript& listed : listedScriptFiles(doc.root)) attempt([&] { host.attach(listed.path, listed.loc); });
  AssetLibrary assetLibrary(buildAssetScene, source.assetTexts);
  for (const DeclaredFile& script : assetLibrary.preload(doc))
    attempt([&] {
      read.scriptFiles.push_back(script.path);
      host.loadScript(script.path, script.loc);
    });
  for (const ListedScript& listed : assetLibrary.usdScripts()) attempt([&] { host.attach(listed.path, listed.loc); });
  failed.throwIfErrors();
  read.scene = buildScene(doc, host.catalog(), source.overrides, &assetLibrary);
  read.mountedFiles = assetLibrary.files();
  read.dropped = assetLibrary.usdLosses().warnings();
  return read;
}

}  // namespace

bool isUsdStagePath(const std::string& path) { return isUsdFile(path); }

SceneSourceRead readSceneSource(const SceneSource& source, SceneScriptHost& host) {
  SceneSourceRead read = isUsdStagePath(source.path) && !source.text ? readUsdStage(source, host)
                                                                      : readYamlScene(source, host);
  for (std::string& file : read.scriptFiles) file = absoluteNormal(file);
  for (std::string& file : read.pluginFiles) file = absoluteNormal(file);
  return read;
}

}  // namespace sdg
