#pragma once
// The loaded stage as one USD layer (`sdgbehave export-usd`), laid out the
// way Isaac Sim expects a stage: Z up, metres, xform ops with xformOpOrder,
// meshes loaded from files written once under `/Prototypes` (a class, not
// drawn) and referenced by each prim that uses them, lights, cameras,
// materials as an OmniPBR MDL shader with a UsdPreviewSurface beside it,
// semantics in Isaac's forms and behaviors as Isaac's behavior extension
// attaches them (omni:scripting:scripts plus typed exposedVar: attributes).
// What has no USD home (render, capture, writers, physics, run settings and
// the pre-roll events) goes into the layer's customLayerData under
// "sdgbehave". The inverse is importUsdScene (usd_import.h).
#include <functional>
#include <string>

#include "assets/asset_resolver.h"
#include "scene_io/scene.h"
#include "stage/behavior_spec.h"
#include "usd/layer.h"

namespace sdg {

// Where Isaac Sim's behavior extension keeps its scripts in a default install.
inline constexpr const char* kIsaacBehaviorScriptsRoot =
    "/isaac-sim/exts/isaacsim.replicator.behavior/isaacsim/replicator/behavior/behaviors";

// A prim's customData key listing the attributes the layer writes only
// for other tools (the stage's fallbacks that USD's schemas do not share,
// such as every gprim's primvars:displayColor): the import leaves them
// unauthored, as they were in the scene.
inline constexpr const char* kFallbacksKey = "sdgbehave:fallbacks";

struct UsdExportOptions {
  // The folder of Isaac's behavior scripts: built-in behaviors are written
  // as <root>/<isaac script file> (locationRandomizer -> location_randomizer.py).
  std::string isaacScriptsRoot = kIsaacBehaviorScriptsRoot;
  // The script file (absolute) a behavior that is not a built-in comes from;
  // "" when it has none (a plugin library's): its exposed variables are
  // still written, and the layer's customLayerData lists it.
  std::function<std::string(const std::string& behavior)> scriptOf;
  // The behaviors' specs: exposed variables that list files in a string
  // ("a.glb#mesh,b.glb") get each file resolved. Null: written as they are.
  const BehaviorCatalog* catalog = nullptr;
};

// Builds the layer. Mesh files are read through `assets` (a RunError names
// the prim when one cannot be read). Deterministic: same scene, same layer.
usd::Layer exportUsdLayer(const Scene& scene, const AssetResolver& assets, const UsdExportOptions& options);

}  // namespace sdg
