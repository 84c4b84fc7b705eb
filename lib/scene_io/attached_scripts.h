#pragma once
// Behavior script files a prim lists in `omni:scripting:scripts`, as Isaac
// Sim attaches them (on a USD prim, or as the same key on a YAML prim): what
// each file stands for.
//
//   a file that exists      runs (sdgbehave's script API or, through the
//                           Isaac layer, Isaac's own): the user's file is
//                           the truth;
//   a missing file named    (a stage saved on an Isaac workstation names
//   like one of Isaac's six  paths into its install) the built-in of that
//                           name stands in, said once per run;
//   --isaac-scripts / run.isaac_scripts force either way for the six.
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/source_loc.h"
#include "scene_io/raw_node.h"

namespace sdg {

enum class IsaacScriptChoice {
  Auto,     // the file when it exists, else the built-in of its name
  Builtin,  // the built-in for Isaac's six file names, whether the file exists or not
  Script,   // always the file: a missing one is an error
};
// "auto" | "builtin" | "script"
std::optional<IsaacScriptChoice> parseIsaacScriptChoice(std::string_view text);
inline constexpr const char* kIsaacScriptChoices = "auto, builtin, script";

// Loads an existing script file into the registry and returns the
// behaviors (namespaces) its classes registered; throws SceneError located
// at `where` when it does not load.
using ScriptFileLoader = std::function<std::vector<std::string>(const std::string& path, const SourceLoc& where)>;

// What one listed file stands for: its behaviors, or why not.
struct AttachedScript {
  std::vector<std::string> behaviors;
  bool builtinStandIn = false;  // a missing Isaac file: the built-in runs instead
  std::string error;
};
AttachedScript resolveAttachedScript(const std::string& path, IsaacScriptChoice choice, const ScriptFileLoader& load,
                                     const SourceLoc& where);

// The YAML side: every `omni:scripting:scripts` entry under `prims:` of a
// scene document, resolved against the folder of the file it is written in
// (absolute, lexically normal), each once, in document order.
struct ListedScript {
  std::string path;
  SourceLoc loc;
};
std::vector<ListedScript> listedScriptFiles(const RawNode& root);
// `omni:scripting:scripts` entry `item` (a path as written at `item.loc`) as
// listedScriptFiles resolves it.
std::string resolveListedScript(const std::string& item, const SourceLoc& loc);

// The scene's `run: isaac_scripts:` read before the scene is built (the
// scripts load before its prims are read); nullopt when absent. A bad value
// is left for the full check.
std::optional<IsaacScriptChoice> isaacScriptSetting(const RawNode& root);

// The note said once per run when built-ins stand in for missing files.
std::string builtinStandInNote(const std::vector<std::string>& missingFiles);

}  // namespace sdg
