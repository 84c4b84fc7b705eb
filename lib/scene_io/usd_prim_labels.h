#pragma once
// What the loader needs from a USD stage's per-prim labels before it imports
// the prims (usd_prim_labels.cpp holds importUsdPrimLabels itself).
#include <string>
#include <vector>

#include "scene_io/usd_import.h"

namespace sdg {

// Isaac's behavior extension names its six scripts by file; these map onto
// the built-ins of the same behavior ("location_randomizer.py" ->
// "locationRandomizer"). "" for any other file name.
std::string builtinForIsaacScript(const std::string& fileName);
// The inverse, for the export: "locationRandomizer" -> "location_randomizer.py"; "" for others.
std::string isaacScriptForBuiltin(const std::string& behaviorName);

// The user behavior scripts (`.py` files that use sdgbehave's script API)
// that the stage's prims list in omni:scripting:scripts, absolute, each
// once, in prim order. The loader registers them in the behavior registry
// before importing the prims, so that their BEHAVIOR_NS is in the catalog
// importUsdPrimLabels attaches from.
std::vector<std::string> usdBehaviorScripts(const usd::ComposedStage& composed);

}  // namespace sdg
