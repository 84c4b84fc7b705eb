// importUsdPrimLabels (scene_io/usd_import.h): a composed prim's material
// binding, semantic labels and behaviors onto its stage prim.
//
// Bindings: `material:binding` (else its :full, then :preview purpose),
// with the relationship's bindMaterialAs as the strength. Collection
// bindings are left out with a warning. The stage binds one material per
// prim, so a Mesh whose GeomSubsets bind materials takes the subset's
// material for the whole mesh when exactly one subset binds one (and the
// mesh binds none itself); with several it keeps its own binding and warns.
//
// Semantics: the Semantics schema (semantic:<instance>:params:semanticType
// + semanticData) and UsdSemantics' LabelsAPI (semantics:labels:<taxonomy>
// token arrays), merged per taxonomy in authored order.
//
// Behaviors: omni:scripting:scripts as Isaac's behavior extension writes it,
// with exposedVar:<behaviorNs>:<variable> attributes as the variables, read
// with the YAML loader's checks (usd_value_node.h).
#include "scene_io/usd_prim_labels.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/text.h"
#include "scene_io/usd_materials.h"
#include "scene_io/usd_value_node.h"
#include "stage/path.h"

namespace sdg {
namespace {

constexpr std::string_view kScriptsAttribute = "omni:scripting:scripts";

std::string fileNameOf(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

std::string whereOf(const SourceLoc& loc) {
  const std::string s = loc.str();
  return s.empty() ? "" : s + ": ";
}

// ---- material binding ------------------------------------------------------

const usd::ComposedProperty* bindingRelationship(const usd::ComposedPrim& prim) {
  for (const char* name : {"material:binding", "material:binding:full", "material:binding:preview"})
    if (const usd::ComposedProperty* p = prim.property(name); p && p->isRelationship && !p->targets.empty()) return p;
  return nullptr;
}

std::string bindingStrength(const usd::ComposedProperty& rel) {
  auto it = rel.metadata.find("bindMaterialAs");
  if (it == rel.metadata.end() || !usd::isText(it->second.kind) || it->second.strings.empty())
    return "weakerThanDescendants";
  return it->second.strings.front();
}

// The material a binding relationship names, checked; nullptr (with an
// error or nothing to say) otherwise.
// A target that is not on the composed stage (a MaterialX .mtlx layer that
// lib/usd cannot read, say) is a warning, as USD's is: the prim keeps its
// displayColor.
const usd::ComposedPrim* boundMaterial(const usd::ComposedStage& composed, const usd::ComposedPrim& prim,
                                       const usd::ComposedProperty& rel, UsdImportReport& report, Diagnostics& diag) {
  const std::string& target = rel.targets.front();
  const usd::ComposedPrim* material = composed.prim(target);
  if (!material || !material->defined) {
    report.losses.note(UsdLossKind::Binding, "a material binding to a prim not on the composed stage", rel.loc,
                       prim.path);
    report.warnings.push_back(whereOf(rel.loc) + prim.path + "." + rel.name + ": the material " + target +
                              " is not on the composed stage (a layer lib/usd cannot read, such as MaterialX's "
                              ".mtlx, or a typo); the prim keeps its primvars:displayColor");
    return nullptr;
  }
  if (material->typeName != "Material") {
    diag.error(rel.loc, prim.path + "." + rel.name + ": targets " + target + ", a " +
                            (material->typeName.empty() ? std::string("typeless prim") : material->typeName) +
                            ", not a Material");
    return nullptr;
  }
  // A material the mapping cannot read (its own warning said so): no
  // binding, so the prim keeps its displayColor.
  if (!usdMaterialIsSupported(composed, *material)) return nullptr;
  return material;
}

void importBinding(const usd::ComposedStage& composed, const usd::ComposedPrim& prim, Prim& stagePrim,
                   const std::function<std::string(const std::string&)>& mapPath, UsdImportReport& report,
                   Diagnostics& diag) {
  for (const usd::ComposedProperty& p : prim.properties)
    if (p.isRelationship && p.name.starts_with("material:binding:collection")) {
      report.losses.note(UsdLossKind::Binding, "a collection-based material binding", p.loc, prim.path);
      report.warnings.push_back(whereOf(p.loc) + prim.path + "." + p.name +
                                ": collection-based material bindings are not read; bind the material on the prims");
    }
  const usd::ComposedProperty* rel = bindingRelationship(prim);
  if (rel) {
    if (const usd::ComposedPrim* material = boundMaterial(composed, prim, *rel, report, diag))
      stagePrim.material() = MaterialBinding{mapPath(material->path), bindingStrength(*rel)};
    return;
  }
  if (prim.typeName != "Mesh") return;
  std::vector<std::pair<const usd::ComposedPrim*, const usd::ComposedProperty*>> subsets;
  for (const std::string& child : prim.children) {
    const usd::ComposedPrim* subset = composed.prim(prim.path + "/" + child);
    if (!subset || subset->typeName != "GeomSubset") continue;
    if (const usd::ComposedProperty* r = bindingRelationship(*subset)) subsets.emplace_back(subset, r);
  }
  if (subsets.size() == 1) {
    if (const usd::ComposedPrim* material = boundMaterial(composed, *subsets[0].first, *subsets[0].second, report, diag))
      stagePrim.material() = MaterialBinding{mapPath(material->path), bindingStrength(*subsets[0].second)};
  } else if (subsets.size() > 1) {
    report.losses.note(UsdLossKind::Binding, "materials bound to several GeomSubsets of one mesh", prim.loc, prim.path);
    report.warnings.push_back(whereOf(prim.loc) + prim.path + ": " + std::to_string(subsets.size()) +
                              " GeomSubsets bind materials; the stage binds one material per prim, so none of "
                              "them is bound (the mesh keeps its displayColor)");
  }
}

// ---- semantics ---------------------------------------------------------------

void addLabel(SemanticLabels& labels, const std::string& taxonomy, const std::string& label) {
  std::vector<std::string>& list = labels[taxonomy];
  if (std::find(list.begin(), list.end(), label) == list.end()) list.push_back(label);
}

bool checkTaxonomy(const std::string& taxonomy, const usd::ComposedProperty& p, const std::string& primPath,
                   Diagnostics& diag) {
  if (path::isIdentifier(taxonomy)) return true;
  diag.error(p.loc, primPath + "." + p.name + ": the taxonomy " + text::quote(taxonomy) +
                        " is not an identifier (e.g. class)");
  return false;
}

std::optional<std::string> textValue(const usd::ComposedProperty* p) {
  if (!p || !usd::isText(p->value.kind) || p->value.isArray || p->value.strings.empty()) return std::nullopt;
  return p->value.strings.front();
}

void importSemantics(const usd::ComposedPrim& prim, Prim& stagePrim, Diagnostics& diag) {
  SemanticLabels& labels = stagePrim.semantics();
  for (const usd::ComposedProperty& p : prim.properties) {
    // The Semantics schema: semantic:<instance>:params:semanticType / semanticData.
    if (p.name.starts_with("semantic:") && p.name.ends_with(":params:semanticType")) {
      const std::string instance = p.name.substr(0, p.name.size() - std::string_view(":params:semanticType").size());
      const usd::ComposedProperty* data = prim.property(instance + ":params:semanticData");
      std::optional<std::string> type = textValue(&p), label = textValue(data);
      if (!type || !label) {
        diag.error(p.loc, prim.path + "." + instance + ": a semantic label needs a string semanticType and "
                                                       "semanticData; found " +
                              (type ? "no semanticData" : "no string semanticType"));
        continue;
      }
      if (label->empty()) {
        diag.error(data->loc, prim.path + "." + data->name + ": labels must not be empty");
        continue;
      }
      if (checkTaxonomy(*type, p, prim.path, diag)) addLabel(labels, *type, *label);
      continue;
    }
    // UsdSemantics' LabelsAPI: semantics:labels:<taxonomy> = token[].
    if (p.name.starts_with("semantics:labels:")) {
      const std::string taxonomy = p.name.substr(std::string_view("semantics:labels:").size());
      if (!checkTaxonomy(taxonomy, p, prim.path, diag)) continue;
      if (!usd::isText(p.value.kind)) {
        diag.error(p.loc, prim.path + "." + p.name + ": expected a token[] of labels, found " +
                              (p.typeName.empty() ? std::string("no value") : p.typeName));
        continue;
      }
      for (const std::string& label : p.value.strings) {
        if (label.empty()) diag.error(p.loc, prim.path + "." + p.name + ": labels must not be empty");
        else addLabel(labels, taxonomy, label);
      }
    }
  }
}

// ---- behaviors ---------------------------------------------------------------

// The behaviors a file listed in omni:scripting:scripts stands for. The
// program's script loader (run/'s ScriptAttacher, behind
// UsdImportOptions::attachScript, or before the import for the files it
// was handed: BehaviorCatalog::attachedScripts) is the only judge of what a
// file defines; without one, Isaac's six scripts stand for the built-ins by
// file name and any other file cannot be attached.
struct ScriptBehaviors {
  std::vector<const BehaviorSpec*> specs;
  std::string error;  // why not, when specs is empty
};

ScriptBehaviors behaviorsForScript(const std::string& resolved, const BehaviorCatalog& catalog,
                                   const UsdImportOptions& options) {
  if (auto attached = catalog.attachedScripts.find(resolved); attached != catalog.attachedScripts.end()) {
    ScriptBehaviors out;
    for (const std::string& name : attached->second) {
      const BehaviorSpec* spec = catalog.find(name);
      if (!spec) return {{}, "the script " + resolved + " defines " + text::quote(name) + ", which is not registered"};
      out.specs.push_back(spec);
    }
    return out;
  }
  const std::string file = fileNameOf(resolved);
  if (options.builtinsForIsaacScripts) {
    const std::string builtin = builtinForIsaacScript(file);
    if (!builtin.empty()) {
      if (const BehaviorSpec* spec = catalog.find(builtin)) return {{spec}, ""};
      return {{}, "the built-in behavior " + text::quote(builtin) + " is not registered"};
    }
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(resolved, ec))
    return {{}, "script " + text::quote(resolved) +
                    " not found (hint: Isaac's behavior scripts are recognised by file name: " +
                    "location_randomizer.py, rotation_randomizer.py, look_at_behavior.py, light_randomizer.py, "
                    "texture_randomizer.py, volume_stack_randomizer.py; any other must be a behavior script that "
                    "exists)"};
  return {{}, "script " + text::quote(resolved) +
                  " was not loaded: the program reading this stage attaches the scripts its prims list before "
                  "importing them (sdgbehave run, validate and inspect do); here only Isaac's six stand for "
                  "built-ins"};
}

void attachBehavior(const usd::ComposedPrim& prim, Prim& stagePrim, const BehaviorSpec& spec,
                    const std::function<std::string(const std::string&)>& mapPath, Diagnostics& diag) {
  const std::string prefix = exposedAttributeName(spec.name, "");
  for (const usd::ComposedProperty& p : prim.properties) {
    if (!p.name.starts_with(prefix) || p.isRelationship) continue;
    const std::string variable = p.name.substr(prefix.size());
    const AttributeSpec* var = spec.findVariable(variable);
    const std::string what = prim.path + "." + p.name;
    if (!var) {
      std::vector<std::string> names = spec.variableNames();
      diag.error(p.loc, what + ": " + spec.name + " has no variable " + text::quote(variable) + "; its variables: " +
                            text::join(names, ", ") + text::didYouMean(variable, names));
      continue;
    }
    // Isaac writes every exposed variable, the informational (locked) ones too.
    if (var->locked || p.value.empty()) continue;
    std::optional<Value> v = readUsdValue(p, *var, what, diag);
    if (!v) continue;
    if (var->primPath && !v->get<std::string>().empty()) {
      const std::string& target = v->get<std::string>();
      if (std::string why = path::whyInvalid(target); !why.empty()) {
        diag.error(p.loc, what + ": " + text::quote(target) + " is not a prim path: " + why);
        continue;
      }
      *v = Value::makeString(mapPath(target));
    }
    Attribute& a = stagePrim.setAttribute(p.name, *v, true);
    a.doc = var->doc;
    a.loc = p.loc;
  }
  createExposedVariables(stagePrim, spec);
  if (std::find(stagePrim.behaviors().begin(), stagePrim.behaviors().end(), spec.name) == stagePrim.behaviors().end())
    stagePrim.behaviors().push_back(spec.name);
}

void importBehaviors(const usd::ComposedPrim& prim, Prim& stagePrim,
                     const std::function<std::string(const std::string&)>& mapPath, const BehaviorCatalog& catalog,
                     const UsdImportOptions& options, Diagnostics& diag) {
  const usd::ComposedProperty* scripts = prim.property(std::string(kScriptsAttribute));
  if (!scripts || scripts->value.empty()) return;
  if (scripts->value.kind != usd::Kind::AssetPath) {
    diag.error(scripts->loc, prim.path + "." + scripts->name + ": expected an asset[] of script paths, found " +
                                 scripts->typeName);
    return;
  }
  const std::vector<std::string>& paths =
      scripts->resolvedAssets.size() == scripts->value.strings.size() ? scripts->resolvedAssets : scripts->value.strings;
  for (const std::string& path : paths) {
    if (options.attachScript) {
      for (const std::string& name : options.attachScript(path, scripts->loc))
        if (const BehaviorSpec* spec = catalog.find(name)) attachBehavior(prim, stagePrim, *spec, mapPath, diag);
      continue;
    }
    ScriptBehaviors b = behaviorsForScript(path, catalog, options);
    if (b.specs.empty()) {
      diag.error(scripts->loc, prim.path + "." + scripts->name + ": " + b.error);
      continue;
    }
    for (const BehaviorSpec* spec : b.specs) attachBehavior(prim, stagePrim, *spec, mapPath, diag);
  }
}

}  // namespace

// Isaac's script file of each built-in behavior (import and export).
const std::pair<const char*, const char*> kIsaacScripts[] = {
    {"location_randomizer.py", "locationRandomizer"}, {"rotation_randomizer.py", "rotationRandomizer"},
    {"look_at_behavior.py", "lookAtBehavior"},         {"light_randomizer.py", "lightRandomizer"},
    {"texture_randomizer.py", "textureRandomizer"},   {"volume_stack_randomizer.py", "volumeStackRandomizer"}};

std::string builtinForIsaacScript(const std::string& fileName) {
  for (const auto& [file, behavior] : kIsaacScripts)
    if (fileName == file) return behavior;
  return "";
}

std::string isaacScriptForBuiltin(const std::string& behaviorName) {
  for (const auto& [file, behavior] : kIsaacScripts)
    if (behaviorName == behavior) return file;
  return "";
}

std::vector<ListedScript> usdListedScripts(const usd::ComposedStage& composed) {
  std::vector<ListedScript> found;
  for (const usd::ComposedPrim& prim : composed.prims) {
    if (!prim.defined || !prim.active) continue;
    const usd::ComposedProperty* scripts = prim.property(std::string(kScriptsAttribute));
    if (!scripts || scripts->value.kind != usd::Kind::AssetPath) continue;
    for (const std::string& path : scripts->resolvedAssets)
      if (std::none_of(found.begin(), found.end(), [&](const ListedScript& l) { return l.path == path; }))
        found.push_back(ListedScript{path, scripts->loc});
  }
  return found;
}

void importUsdPrimLabels(const usd::ComposedStage& composed, const usd::ComposedPrim& prim, Prim& stagePrim,
                         const std::function<std::string(const std::string&)>& mapPath,
                         const BehaviorCatalog& catalog, const UsdImportOptions& options, UsdImportReport& report,
                         Diagnostics& diag) {
  importBinding(composed, prim, stagePrim, mapPath, report, diag);
  importSemantics(prim, stagePrim, diag);
  importBehaviors(prim, stagePrim, mapPath, catalog, options, diag);
}

}  // namespace sdg
