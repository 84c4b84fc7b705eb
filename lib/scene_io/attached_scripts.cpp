#include "scene_io/attached_scripts.h"

#include <algorithm>
#include <filesystem>

#include "core/text.h"
#include "scene_io/usd_prim_labels.h"

namespace fs = std::filesystem;

namespace sdg {

std::optional<IsaacScriptChoice> parseIsaacScriptChoice(std::string_view text) {
  if (text == "auto") return IsaacScriptChoice::Auto;
  if (text == "builtin") return IsaacScriptChoice::Builtin;
  if (text == "script") return IsaacScriptChoice::Script;
  return std::nullopt;
}

AttachedScript resolveAttachedScript(const std::string& path, IsaacScriptChoice choice, const ScriptFileLoader& load,
                                     const SourceLoc& where) {
  const std::string file = fs::path(path).filename().string();
  const std::string builtin = builtinForIsaacScript(file);
  std::error_code ec;
  const bool exists = fs::is_regular_file(path, ec);
  if (!builtin.empty() && (choice == IsaacScriptChoice::Builtin || (!exists && choice == IsaacScriptChoice::Auto)))
    return AttachedScript{{builtin}, !exists, ""};
  if (exists) return AttachedScript{load(path, where), false, ""};
  std::string error = "script " + text::quote(path) + " not found";
  if (!builtin.empty())
    error += " (isaac_scripts is 'script', so the built-in " + text::quote(builtin) +
             " does not stand in for it; --isaac-scripts auto lets it)";
  else
    error += " (hint: only Isaac's six behavior scripts have built-in stand-ins: location_randomizer.py, "
             "rotation_randomizer.py, look_at_behavior.py, light_randomizer.py, texture_randomizer.py, "
             "volume_stack_randomizer.py)";
  return AttachedScript{{}, false, error};
}

std::string resolveListedScript(const std::string& item, const SourceLoc& loc) {
  fs::path p(item);
  if (p.is_relative()) p = fs::path(loc.file.str()).parent_path() / p;
  return fs::absolute(p).lexically_normal().string();
}

namespace {

void collectListed(const RawNode& node, std::vector<ListedScript>& out) {
  if (!node.isMap()) return;
  for (const RawEntry& e : node.entries) {
    if (e.key.scalar == "omni:scripting:scripts" && e.value.isSequence()) {
      for (const RawNode& item : e.value.items) {
        if (!item.isScalar() || item.scalar.empty()) continue;
        std::string path = resolveListedScript(item.scalar, item.loc);
        if (std::none_of(out.begin(), out.end(), [&](const ListedScript& s) { return s.path == path; }))
          out.push_back({path, item.loc});
      }
      continue;
    }
    collectListed(e.value, out);
  }
}

}  // namespace

std::vector<ListedScript> listedScriptFiles(const RawNode& root) {
  std::vector<ListedScript> out;
  if (const RawNode* prims = root.isMap() ? root.find("prims") : nullptr) collectListed(*prims, out);
  return out;
}

std::optional<IsaacScriptChoice> isaacScriptSetting(const RawNode& root) {
  const RawNode* run = root.isMap() ? root.find("run") : nullptr;
  const RawNode* value = run && run->isMap() ? run->find("isaac_scripts") : nullptr;
  return value && value->isScalar() ? parseIsaacScriptChoice(value->scalar) : std::nullopt;
}

std::string builtinStandInNote(const std::vector<std::string>& missingFiles) {
  std::vector<std::string> names;
  for (const std::string& f : missingFiles) names.push_back(f + " -> " + builtinForIsaacScript(fs::path(f).filename().string()));
  return "Isaac behavior script" + std::string(missingFiles.size() == 1 ? " " : "s ") + "not found, the built-in" +
         (missingFiles.size() == 1 ? " stands" : "s stand") + " in: " + text::join(names, ", ") +
         " (--isaac-scripts script makes a missing file an error)";
}

}  // namespace sdg
