#pragma once
// A composed USD stage (usd/compose.h) onto sdgbehave's Stage: the one
// place that knows both. After it, nothing downstream knows a prim came
// from USD.
//
//   importUsdScene       the driver (usd_import.cpp): the prim tree, types,
//                        xform ops, geometry (gprims, Mesh with its primvars
//                        and GeomSubsets), lights, cameras, units and up axis
//                        (the stage is Z-up metres: the root layer's units and
//                        each referenced layer's `unitsChange` become
//                        correcting transforms), `active`/`instanceable`,
//                        the defaults a USD stage does not say (writer,
//                        capture), and the calls below for each prim.
//   importUsdMaterial    materials (usd_materials.cpp): UsdPreviewSurface with
//                        UsdUVTexture / UsdPrimvarReader_float2 /
//                        UsdTransform2d, and Isaac's MDL OmniPBR by its
//                        inputs, onto a stage Material prim; anything else
//                        falls back with one warning naming the material.
//   importUsdPrimLabels  per prim (usd_prim_labels.cpp): material binding
//                        (material:binding, GeomSubset bindings as the
//                        driver hands them), semantics in both of Isaac's
//                        forms, and behaviors as Isaac attaches them
//                        (omni:scripting:scripts + exposedVar:<ns>:<name>).
//
// Problems go to `diag` located at the USD file:line:col of the opinion
// (ComposedPrim::loc / ComposedProperty::loc), so `validate stage.usda`
// reports them as it reports a YAML scene's.
#include <functional>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "scene_io/scene.h"
#include "scene_io/usd_losses.h"
#include "stage/behavior_spec.h"
#include "usd/compose.h"

namespace sdg {

struct UsdImportOptions {
  // --set style variant choices: prim path -> variant set -> variant.
  usd::VariantOverrides variants;
  // Where each choice was made ("PRIM SET" -> the --set or YAML value), so
  // that a set or variant the stage lacks is reported there.
  std::map<std::string, SourceLoc> variantLocs;
  // A framing camera and lights where the stage has none, and the default
  // writer and capture: for a stage run on its own, not for one mounted in
  // a YAML scene.
  bool runDefaults = true;
  // Without attachScript, Isaac's six behavior scripts named by file stand
  // in for the built-ins of the same name; a file the catalog records as
  // attached (BehaviorCatalog::attachedScripts, the loader's work) stands
  // for what it defined.
  bool builtinsForIsaacScripts = true;
  // What each file listed in omni:scripting:scripts stands for, decided by
  // the program's script loader (run/'s ScriptAttacher:
  // scene_io/attached_scripts.h), loading scripts as they are met; throws
  // SceneError at `where` when a file cannot be attached.
  std::function<std::vector<std::string>(const std::string& path, const SourceLoc& where)> attachScript;
};

// What importing found besides the stage: every layer read (for the run's
// identity), what the stage does not carry over: counted by kind (`losses`,
// what commands print) and each place in words (`warnings`, for --verbose).
struct UsdImportReport {
  std::vector<std::string> layers;
  UsdLosses losses;
  std::vector<std::string> warnings;
};

// The suffix of the ops that correct a USD file's units and up axis
// (xformOp:rotateX:unitsResolve, xformOp:scale:unitsResolve), as Omniverse
// names them: a YAML override of a mounted USD prim's ops keeps them.
inline constexpr std::string_view kUnitsResolveSuffix = "unitsResolve";

// A USD layer or package by its extension: .usd, .usda, .usdc, .usdz (any case).
bool isUsdFile(const std::string& path);

// The options a run's --set overrides give: their variant selections
// (PRIM.variants:SET=VARIANT). SceneError (exit 2) for a malformed one.
UsdImportOptions usdImportOptionsFor(std::span<const std::string> overrides);

// The whole scene of a USD stage file (`sdgbehave run stage.usda`). Throws
// SceneError (exit 2) with every problem located.
Scene importUsdScene(const std::string& path, const BehaviorCatalog& catalog, const UsdImportOptions& options,
                     UsdImportReport& report);

// The composed prims under `sourceRoot` of `composed` defined at
// `mountPath` of `stage` (whose parent exists): a YAML `reference:` to a
// USD file, or the whole stage for importUsdScene ("/" → "/").
void importUsdPrims(const usd::ComposedStage& composed, const std::string& sourceRoot, Stage& stage,
                    const std::string& mountPath, const BehaviorCatalog& catalog, const UsdImportOptions& options,
                    UsdImportReport& report, Diagnostics& diag);

// A Material prim (and its shader network below it) as a stage Material at
// `stagePath` (already defined by the driver as PrimType::Material).
void importUsdMaterial(const usd::ComposedStage& composed, const usd::ComposedPrim& material, Prim& stagePrim,
                       Diagnostics& diag, UsdImportReport& report);

// Binding, semantics and behaviors of one prim. `mapPath` turns a path of
// the composed stage into the stage path it was imported at (bindings and
// behaviors' prim-path variables point into the stage).
void importUsdPrimLabels(const usd::ComposedStage& composed, const usd::ComposedPrim& prim, Prim& stagePrim,
                         const std::function<std::string(const std::string&)>& mapPath,
                         const BehaviorCatalog& catalog, const UsdImportOptions& options, UsdImportReport& report,
                         Diagnostics& diag);

}  // namespace sdg
