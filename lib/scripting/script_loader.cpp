#include "scripting/script_loader.h"

#include <filesystem>
#include <map>
#include <regex>

#include <pybind11/embed.h>
#include <pybind11/stl.h>

#include "behavior/run_activity.h"
#include "core/diagnostics.h"
#include "core/log.h"
#include "core/text.h"
#include "scripting/python_host.h"
#include "scripting/script_behavior.h"
#include "scripting/script_call.h"
#include "scripting/value_convert.h"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace sdg::scripting {
namespace {

// One behavior class of a loaded script, ready to register.
struct ScriptedBehavior {
  BehaviorSpec spec;
  py::object cls;
  std::string rngStream;
  SourceLoc loc;  // the class statement
  bool isaac = false;  // an Isaac Sim BehaviorScript (omni.behavior.scripting.core)
};

struct LoadedScript {
  std::string source;  // the path as first given: shown by describe and in messages
  std::vector<ScriptedBehavior> behaviors;
};

// Scripts run once per process, whichever registries they are added to.
std::map<std::string, LoadedScript>& loadedScripts() {
  static auto* scripts = new std::map<std::string, LoadedScript>();  // holds Python objects: never destroyed
  return *scripts;
}

const std::vector<std::string>& recordKeys() {
  static const std::vector<std::string> keys = {"attr_name", "attr_type", "default_value", "doc", "lock",
                                                "minimum", "allowed", "prim_path", "files"};
  return keys;
}

bool isAttributeName(const std::string& name) {
  static const std::regex pattern("[A-Za-z_][A-Za-z0-9_]*(:[A-Za-z_][A-Za-z0-9_]*)*");
  return std::regex_match(name, pattern);
}

std::string typeNames() {
  std::vector<std::string> names;
  for (ValueType t : allValueTypes()) names.emplace_back(valueTypeName(t));
  return text::join(names, ", ");
}

// One VARIABLES_TO_EXPOSE record -> an AttributeSpec, or a problem at `loc`.
AttributeSpec readVariable(py::handle record, const std::string& ns, const SourceLoc& loc, Diagnostics& diag) {
  AttributeSpec spec;
  const std::string where = ns + ": VARIABLES_TO_EXPOSE";
  if (!py::isinstance<py::dict>(record)) {
    diag.error(loc, where + ": each entry is a dict {\"attr_name\", \"attr_type\", \"default_value\", \"doc\"}, found " +
                        std::string(py::repr(record)));
    return spec;
  }
  py::dict d = py::reinterpret_borrow<py::dict>(record);
  const size_t errorsBefore = diag.errorCount();
  auto failed = [&] { return diag.errorCount() != errorsBefore; };
  for (auto [key, value] : d) {
    std::string k = py::str(key);
    if (std::find(recordKeys().begin(), recordKeys().end(), k) == recordKeys().end())
      diag.error(loc, where + ": unknown key '" + k + "'" + text::didYouMean(k, recordKeys()) + "; the keys are " +
                          text::join(recordKeys(), ", "));
  }
  for (const char* required : {"attr_name", "attr_type", "default_value", "doc"})
    if (!d.contains(required)) diag.error(loc, where + ": the entry lacks '" + std::string(required) + "'");
  if (failed()) return spec;

  if (!py::isinstance<py::str>(d["attr_name"]) || !isAttributeName(d["attr_name"].cast<std::string>())) {
    diag.error(loc, where + ": attr_name must be a name such as 'interval' or 'range:minPosition', found " +
                        std::string(py::repr(d["attr_name"])));
    return spec;
  }
  spec.name = d["attr_name"].cast<std::string>();
  const std::string what = ns + "." + spec.name;
  std::optional<ValueType> type;
  if (py::isinstance<py::str>(d["attr_type"])) type = valueTypeFromName(d["attr_type"].cast<std::string>());
  if (!type) {
    std::string found = py::repr(d["attr_type"]);
    diag.error(loc, what + ": attr_type must be a USD type name (" + typeNames() + "), found " + found +
                        (py::isinstance<py::str>(d["attr_type"])
                             ? text::didYouMean(d["attr_type"].cast<std::string>(), [] {
                                 std::vector<std::string> n;
                                 for (ValueType t : allValueTypes()) n.emplace_back(valueTypeName(t));
                                 return n;
                               }())
                             : std::string()));
    return spec;
  }
  spec.type = *type;
  try {
    spec.defaultValue = fromPython(d["default_value"], spec.type, what + " default_value");
  } catch (const py::builtin_exception& e) {
    diag.error(loc, e.what());
    return spec;
  } catch (py::error_already_set& e) {
    diag.error(loc, what + " default_value: " + std::string(py::str(e.value())));
    return spec;
  }
  if (!py::isinstance<py::str>(d["doc"])) diag.error(loc, what + ": doc must be a string");
  else spec.doc = d["doc"].cast<std::string>();
  if (d.contains("lock")) {
    if (!py::isinstance<py::bool_>(d["lock"])) diag.error(loc, what + ": lock must be True or False");
    else spec.locked = d["lock"].cast<bool>();
  }
  if (d.contains("minimum")) {
    py::handle m = d["minimum"];
    if (py::isinstance<py::bool_>(m) || !PyNumber_Check(m.ptr())) diag.error(loc, what + ": minimum must be a number");
    else spec.minimum = m.cast<double>();
  }
  if (d.contains("allowed")) {
    if (spec.type != ValueType::Token) diag.error(loc, what + ": allowed is for token variables");
    else {
      try {
        spec.allowedTokens = d["allowed"].cast<std::vector<std::string>>();
      } catch (const py::cast_error&) {
        diag.error(loc, what + ": allowed must be a list of strings");
      }
    }
  }
  if (d.contains("prim_path")) {
    if (spec.type != ValueType::String || !py::isinstance<py::bool_>(d["prim_path"]))
      diag.error(loc, what + ": prim_path is True or False, for string variables");
    else spec.primPath = d["prim_path"].cast<bool>();
  }
  if (d.contains("files")) {
    std::string kind = py::isinstance<py::str>(d["files"]) ? d["files"].cast<std::string>() : "";
    bool fileType = spec.type == ValueType::String || spec.type == ValueType::Asset || spec.type == ValueType::AssetArray;
    if (!fileType || (kind != "mesh" && kind != "image" && kind != "any"))
      diag.error(loc, what + ": files is 'mesh', 'image' or 'any', for string, asset and asset[] variables");
    else spec.files = kind == "mesh" ? FileKind::Mesh : kind == "image" ? FileKind::Image : FileKind::Any;
  }
  return spec;
}

ScriptedBehavior readBehaviorClass(const py::tuple& found, const std::string& file, Diagnostics& diag) {
  ScriptedBehavior b;
  b.cls = found[0];
  b.isaac = py::hasattr(b.cls, "_isaac_script");
  const std::string className = found[1].cast<std::string>();
  const SourceLoc classLoc{file, found[2].cast<int>(), 1};
  b.loc = classLoc;
  const SourceLoc varsLoc{file, found[3].cast<int>(), 1};
  std::vector<std::pair<int, int>> entryLines = found[4].cast<std::vector<std::pair<int, int>>>();
  py::object ns = b.cls.attr("BEHAVIOR_NS");
  if (!py::isinstance<py::str>(ns) || !isAttributeName(ns.cast<std::string>()) ||
      ns.cast<std::string>().find(':') != std::string::npos) {
    diag.error(classLoc, className + ": BEHAVIOR_NS must be a camelCase name such as 'randomScale', found " +
                             std::string(py::repr(ns)));
    return b;
  }
  b.spec.name = ns.cast<std::string>();
  py::object stream = b.cls.attr("RNG_STREAM");
  if (!stream.is_none() && !py::isinstance<py::str>(stream))
    diag.error(classLoc, b.spec.name + ": RNG_STREAM must be a string or None");
  b.rngStream = stream.is_none() || !py::isinstance<py::str>(stream) ? b.spec.name : stream.cast<std::string>();

  py::object doc = b.cls.attr("__doc__");
  std::string summary = py::isinstance<py::str>(doc) ? doc.cast<std::string>() : "";
  summary = summary.substr(0, summary.find("\n\n"));
  for (char& c : summary)
    if (c == '\n') c = ' ';
  summary = std::regex_replace(summary, std::regex("\\s+"), " ");
  while (!summary.empty() && summary.front() == ' ') summary.erase(0, 1);
  while (!summary.empty() && summary.back() == ' ') summary.pop_back();
  b.spec.summary = summary.empty() ? "A scripted behavior (" + className + ")." : summary;

  py::object variables = found[5];
  if (!py::isinstance<py::list>(variables) && !py::isinstance<py::tuple>(variables)) {
    diag.error(varsLoc, b.spec.name + ": VARIABLES_TO_EXPOSE must be a list of records, found " +
                            std::string(py::repr(variables)));
    return b;
  }
  size_t i = 0;
  for (py::handle record : variables) {
    SourceLoc loc = i < entryLines.size() ? SourceLoc{file, entryLines[i].first, entryLines[i].second} : varsLoc;
    ++i;
    AttributeSpec var = readVariable(record, b.spec.name, loc, diag);
    if (var.name.empty()) continue;
    if (b.spec.findVariable(var.name)) {
      diag.error(loc, b.spec.name + "." + var.name + ": declared twice in VARIABLES_TO_EXPOSE");
      continue;
    }
    b.spec.variables.push_back(std::move(var));
  }
  const bool interval = py::cast<bool>(
      py::module_::import("builtins").attr("issubclass")(b.cls, PythonHost::instance().api().attr("IntervalBehavior")));
  const bool updates = !b.cls.attr("on_update").is(PythonHost::instance().api().attr("Behavior").attr("on_update"));
  b.spec.eventDriven = !interval && !updates;
  b.spec.example = b.spec.name + ": {}";
  return b;
}

LoadedScript runScript(const std::string& path, const std::string& canonical) {
  PythonHost& host = PythonHost::instance();
  host.addScriptFile(canonical, path);
  static int counter = 0;
  std::string stem = fs::path(path).stem().string();
  for (char& c : stem)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  const std::string moduleName = "sdgbehave_script_" + std::to_string(++counter) + "_" + stem;
  py::list found;
  try {
    activity::HookScope loading(path, "", "", activity::HookScope::Kind::Loading);
    found = host.api().attr("_load_script")(canonical, moduleName);
  } catch (py::error_already_set& e) {
    PythonHost::ErrorInfo info = host.describe(e);
    SourceLoc loc = info.loc.known() ? info.loc : SourceLoc{path, 0, 0};
    if (std::string exit = exitCall(e); !exit.empty())
      throw SceneError(loc, "loading the script failed: its top-level code called " + exit +
                                ", which a script cannot do; raise an exception instead:\n" + info.text);
    throw SceneError(loc, "loading the script failed:\n" + info.text);
  }
  LoadedScript script{path, {}};
  Diagnostics diag;
  for (py::handle item : found) {
    ScriptedBehavior b = readBehaviorClass(item.cast<py::tuple>(), path, diag);
    if (b.spec.name.empty()) continue;
    for (const ScriptedBehavior& other : script.behaviors)
      if (other.spec.name == b.spec.name)
        diag.error(SourceLoc{path, item.cast<py::tuple>()[2].cast<int>(), 1},
                   "BEHAVIOR_NS '" + b.spec.name + "' is used by two classes of this script");
    script.behaviors.push_back(std::move(b));
  }
  if (found.empty())
    diag.error(SourceLoc{path, 1, 1}, "the script defines no behavior: a class deriving from sdgbehave.Behavior (or "
                                      "sdgbehave.IntervalBehavior) with its own BEHAVIOR_NS");
  diag.throwIfErrors();
  return script;
}

}  // namespace

void checkScriptFile(const std::string& path, const SourceLoc& where) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found || (ec && status.type() == fs::file_type::none))
    throw SceneError(where, "script " + text::quote(path) + " not found");
  if (status.type() == fs::file_type::directory)
    throw SceneError(where, "script " + text::quote(path) + " is a folder; give the Python file (.py) itself");
  if (status.type() != fs::file_type::regular)
    throw SceneError(where, "script " + text::quote(path) + " is not a regular file");
  const std::string extension = fs::path(path).extension().string();
  if (extension != ".py") {
    const bool scene = extension == ".yaml" || extension == ".yml";
    throw SceneError(where, "script " + text::quote(path) + " is not a Python file: behavior scripts end in .py" +
                                (scene ? std::string("; a scene is the command's SCENE argument") : std::string()));
  }
}

void reloadScript(const std::string& path) {
  std::error_code ec;
  const std::string canonical = fs::canonical(path, ec).string();
  if (ec) throw SceneError(SourceLoc{path, 0, 0}, "script " + text::quote(path) + " not found");
  auto it = loadedScripts().find(canonical);
  const std::string source = it == loadedScripts().end() ? path : it->second.source;
  LoadedScript fresh = runScript(source, canonical);  // throws, leaving the old version in place
  loadedScripts()[canonical] = std::move(fresh);
}

std::vector<std::string> loadScript(BehaviorRegistry& registry, const std::string& path, const SourceLoc& where) {
  checkScriptFile(path, where);
  std::error_code ec;
  const std::string canonical = fs::canonical(path, ec).string();
  auto it = loadedScripts().find(canonical);
  if (it == loadedScripts().end()) it = loadedScripts().emplace(canonical, runScript(path, canonical)).first;
  const LoadedScript& script = it->second;
  std::vector<std::string> names;
  for (const ScriptedBehavior& b : script.behaviors) {
    names.push_back(b.spec.name);
    if (b.isaac && registry.catalog().find(b.spec.name) && registry.sourceOf(b.spec.name) == "built-in") {
      log::info(b.spec.name + ": the Isaac Sim script " + script.source + " stands in for the built-in behavior");
      py::object cls = b.cls;
      std::string rngStream = b.rngStream, source = script.source;
      registry.replaceBuiltin(
          b.spec, [cls, rngStream, source] { return std::make_unique<ScriptBehavior>(cls, rngStream, source); },
          script.source);
      continue;
    }
    if (registry.catalog().find(b.spec.name)) {
      const std::string& other = registry.sourceOf(b.spec.name);
      if (other == script.source) continue;  // this script, loaded again (another asset, --script and scripts:)
      throw SceneError(b.loc, "BEHAVIOR_NS '" + b.spec.name + "' " +
                                  (other == "built-in" ? std::string("is the name of a built-in behavior")
                                                       : "is already defined by " + other) +
                                  "; give this class another BEHAVIOR_NS (the script was loaded from " +
                                  (where.known() ? where.str() : path) + ")");
    }
    py::object cls = b.cls;
    std::string rngStream = b.rngStream;
    std::string source = script.source;
    registry.add(b.spec, [cls, rngStream, source] { return std::make_unique<ScriptBehavior>(cls, rngStream, source); },
                 script.source);
  }
  return names;
}

}  // namespace sdg::scripting
