#pragma once
// Smart assets: a prim's `reference:` mounts the prim tree of another scene
// file (an asset) at the prim's path, with its types, meshes, materials,
// labels, behaviors and exposed-variable values, as a USD reference does.
// What the referencing scene writes on that prim and below is a local
// override (readPrims applies it on top of the mounted tree).
//
// An asset is an ordinary scene file: it validates and renders on its own.
// When referenced, its prims and its scripts are used; its render, capture,
// writer, events and physics settings apply only when it runs on its own.
// Relative paths inside an asset (meshes, textures, scripts, nested
// references) resolve against the asset's own folder and asset_roots; on
// mounting they are rewritten relative to the referencing file's folder, so
// the flattened stage names the same files. Each asset file is read and
// checked once per load, however often it is referenced; every mounted
// value keeps its location in the asset, with "referenced from" the
// referencing prim's `reference:`.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "scene_io/attached_scripts.h"
#include "scene_io/overrides.h"
#include "scene_io/raw_node.h"
#include "scene_io/scene.h"
#include "scene_io/usd_losses.h"
#include "scene_io/scene_document.h"
#include "stage/behavior_spec.h"
#include "stage/stage.h"
#include "usd/compose.h"

namespace sdg {

// Documented limit: references nested deeper than this are refused.
inline constexpr size_t kMaxReferenceDepth = 32;

// What a `reference:` names: `reference: assets/drill.yaml` or
// `reference: {file: assets/drill.yaml, prim: /Drill}`.
//
// A USD file (.usd, .usda, .usdc, .usdz) mounts the same way: the prim
// named (else the layer's defaultPrim, else its first root prim) and its
// subtree, imported as a USD stage is (usd_import.h), with variant
// selections for that prim: `reference: {file: chair.usda, variants:
// {color: red}}` (USD files only).
struct ReferenceSpec {
  std::string file;  // as written, relative to the referencing file's folder
  std::string prim;  // "" = the asset's first top-level prim (a USD file's defaultPrim)
  std::map<std::string, std::string> variants;  // variant set -> variant, on the mounted prim
  SourceLoc loc;     // the `reference:` value
};
std::optional<ReferenceSpec> readReferenceSpec(const RawNode& node, const std::string& what, Diagnostics& diag);

class AssetLibrary;
// Builds a referenced asset's document into a scene (the scene loader's
// buildAssetScene), mounting the asset's own references from `assets`.
using AssetSceneBuilder = Scene (*)(const SceneDocument& doc, const BehaviorCatalog& catalog, AssetLibrary& assets);

class AssetLibrary {
 public:
  // `texts` replaces what is on disk for some asset files (absolute,
  // normalized paths): the studio's edits of an asset not saved yet.
  explicit AssetLibrary(AssetSceneBuilder build, std::map<std::string, std::string> texts = {});
  ~AssetLibrary();
  AssetLibrary(const AssetLibrary&) = delete;
  AssetLibrary& operator=(const AssetLibrary&) = delete;

  // Reads every asset `doc` references, recursively, and returns the
  // scripts those assets declare (absolute paths, located), so that their
  // behaviors can be registered before any prim is read. Cycles, nesting
  // beyond kMaxReferenceDepth and missing files throw SceneError located at
  // the reference (and the chain that led to it).
  // The script files that the prims of mounted USD files list in
  // omni:scripting:scripts are collected too (usdScripts()): the program's
  // loader attaches them before the scene is built, as it does a YAML
  // scene's own listed scripts.
  std::vector<DeclaredFile> preload(const SceneDocument& doc);
  // Files listed in omni:scripting:scripts by the USD files preload met,
  // each once, located at the reference that mounts its file.
  const std::vector<ListedScript>& usdScripts() const { return usdScripts_; }

  // Defines the referenced prim tree at `mountPath` (its parent exists, the
  // path is free). `fromDir` is the referencing file's folder. Problems go
  // to `diag`; a broken asset reports its own problems, referenced from
  // `ref.loc`.
  void mount(const ReferenceSpec& ref, const std::string& fromDir, const std::string& mountPath, Stage& stage,
             const BehaviorCatalog& catalog, Diagnostics& diag);

  // `--set PRIM.variants:SET=VARIANT` selections: those at or under the
  // mount point of a USD reference of the top-level scene apply to it.
  void setVariantSelections(std::vector<VariantSelection> selections) {
    selections_ = std::move(selections);
    selectionUsed_.assign(selections_.size(), false);
  }
  // The selections no USD reference took (each an error for the caller).
  std::vector<VariantSelection> unusedVariantSelections() const;

  // Every asset script loaded through preload (absolute, in load order).
  const std::vector<std::string>& scripts() const { return scripts_; }
  // How many asset files were read (each once).
  size_t filesRead() const { return assets_.size(); }
  // Every asset file read (absolute, normalized, sorted).
  std::vector<std::string> files() const;
  // What the USD files mounted so far have that the stage does not carry over.
  const UsdLosses& usdLosses() const { return usdLosses_; }

 private:
  struct Asset;
  Asset& document(const std::string& absolutePath, const SourceLoc& from);
  void preloadFrom(const SceneDocument& doc, std::vector<std::string>& chain, const SourceLoc& via,
                   std::vector<DeclaredFile>& scripts);
  const Scene* built(Asset& asset, const BehaviorCatalog& catalog, const SourceLoc& from, Diagnostics& diag);

  void mountUsd(const ReferenceSpec& ref, const std::string& file, const std::string& mountPath, Stage& stage,
                const BehaviorCatalog& catalog, Diagnostics& diag);

  std::map<std::string, std::unique_ptr<Asset>> assets_;  // by absolute normalized path
  // A USD file composed with these variant choices, once per load (a file
  // mounted many times is read once); UsdError when it does not compose.
  const usd::ComposedStage& usdStage(const std::string& file, const usd::ComposeOptions& options);

  std::map<std::string, std::shared_ptr<const usd::ComposedStage>> usdStages_;  // by file and choices
  UsdLosses usdLosses_;
  std::vector<std::string> usdFiles_;                       // USD layers (packages) mounted, absolute
  std::vector<VariantSelection> selections_;
  std::vector<bool> selectionUsed_;
  std::vector<std::string> building_;                       // the chain being built, for cycles
  std::vector<std::string> scripts_;
  std::vector<ListedScript> usdScripts_;
  std::map<std::string, std::string> texts_;
  AssetSceneBuilder build_;
};

// An asset file's key in AssetLibrary's `texts`: absolute and normalized.
std::string assetKey(const std::string& path);

// `loc` with "referenced from `from`" appended to its chain.
SourceLoc referencedFrom(const SourceLoc& loc, const SourceLoc& from);

}  // namespace sdg
