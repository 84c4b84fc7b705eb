#pragma once
// What the loader needs from a USD stage's per-prim labels before it imports
// the prims (usd_prim_labels.cpp holds importUsdPrimLabels itself).
#include <string>
#include <vector>

#include "scene_io/attached_scripts.h"
#include "scene_io/usd_import.h"

namespace sdg {

// Isaac's behavior extension names its six scripts by file; these map onto
// the built-ins of the same behavior ("location_randomizer.py" ->
// "locationRandomizer"). "" for any other file name.
std::string builtinForIsaacScript(const std::string& fileName);
// The inverse, for the export: "locationRandomizer" -> "location_randomizer.py"; "" for others.
std::string isaacScriptForBuiltin(const std::string& behaviorName);

// Every file the stage's prims list in omni:scripting:scripts (resolved,
// each once, in prim order, with the first place that lists it), whatever
// it holds: the program's script loader decides what each stands for
// (run/'s ScriptAttacher) and attaches them before the prims are imported.
std::vector<ListedScript> usdListedScripts(const usd::ComposedStage& composed);

}  // namespace sdg
