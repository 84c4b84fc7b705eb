#include "scene_io/prim_reader.h"

#include <algorithm>
#include <functional>
#include <unordered_map>

#include "core/text.h"
#include "scene_io/attached_scripts.h"
#include "scene_io/map_reader.h"
#include "scene_io/references.h"
#include "scene_io/usd_import.h"
#include "scene_io/value_reader.h"
#include "stage/path.h"

namespace sdg {
namespace {

struct PrimDecl {
  std::string path;
  PrimType type = PrimType::Xform;
  const RawNode* entry = nullptr;
  SourceLoc loc;
  const RawNode* typeNode = nullptr;       // the entry's `type:`, if any
  std::optional<ReferenceSpec> reference;  // the entry's `reference:`, if any
  bool over = false;     // the prim came from a referenced asset: the entry overrides its values
  bool defined = false;  // declared (or mounted) without problems, so it gets filled
};

std::vector<std::string> primTypeNames() {
  std::vector<std::string> names;
  for (const PrimTypeInfo& info : allPrimTypes()) names.emplace_back(info.name);
  return names;
}

void readSemantics(const RawNode& node, const std::string& what, Prim& prim, Diagnostics& diag) {
  MapReader map(node, what, diag);
  if (!map.ok()) return;
  for (const auto& [key, value] : node.entries) {
    map.allow(key.scalar);
    std::string keyWhat = joinWhat(what, key.scalar);
    if (!path::isIdentifier(key.scalar)) {
      diag.error(key.loc, keyWhat + ": a taxonomy name must be an identifier (e.g. class)");
      continue;
    }
    std::vector<std::string> labels;
    if (value.isScalar()) {
      labels.push_back(value.scalar);
    } else if (auto v = readValue(value, ValueType::StringArray, keyWhat, diag)) {
      labels = v->get<std::vector<std::string>>();
    } else {
      continue;
    }
    bool ok = true;
    for (const std::string& label : labels)
      if (label.empty()) {
        diag.error(value.loc, keyWhat + ": labels must not be empty");
        ok = false;
      }
    if (ok) prim.semantics()[key.scalar] = std::move(labels);
  }
}

void readMaterialBinding(const RawNode& node, const std::string& what, Prim& prim, Diagnostics& diag) {
  MaterialBinding binding;
  if (node.isScalar()) {
    binding.path = node.scalar;
  } else {
    MapReader map(node, what, diag);
    if (!map.ok()) return;
    if (const RawNode* p = map.require("path"))
      if (auto s = readString(*p, joinWhat(what, "path"), diag)) binding.path = *s;
    if (const RawNode* s = map.get("strength")) {
      AttributeSpec spec;
      spec.type = ValueType::Token;
      spec.allowedTokens = {"weakerThanDescendants", "strongerThanDescendants"};
      if (auto v = readValue(*s, spec, joinWhat(what, "strength"), diag)) binding.strength = v->get<std::string>();
    }
    map.finish();
  }
  if (std::string why = path::whyInvalid(binding.path); !why.empty()) {
    diag.error(node.loc, what + ": " + text::quote(binding.path) + " is not a prim path: " + why);
    return;
  }
  prim.material() = binding;
}

void readCustomAttributes(const RawNode& node, const std::string& what, Prim& prim, Diagnostics& diag) {
  MapReader map(node, what, diag);
  if (!map.ok()) return;
  for (const auto& [key, value] : node.entries) {
    map.allow(key.scalar);
    std::string attrWhat = prim.path() + "." + key.scalar;
    if (!isValidAttributeName(key.scalar)) {
      diag.error(key.loc, attrWhat + ": an attribute name is identifiers joined by ':' (e.g. user:weight)");
      continue;
    }
    if (findSchemaAttribute(prim.type(), key.scalar) || parseXformOpName(key.scalar)) {
      diag.error(key.loc, attrWhat + ": " + text::quote(key.scalar) +
                              " is a built-in attribute of the prim; set it directly on the prim, not under attributes");
      continue;
    }
    MapReader entry(value, attrWhat, diag);
    if (!entry.ok()) continue;
    const RawNode* typeNode = entry.require("type");
    const RawNode* valueNode = entry.require("value");
    const RawNode* docNode = entry.get("doc");
    entry.finish();
    if (!typeNode || !valueNode) continue;
    auto typeName = readString(*typeNode, attrWhat + ".type", diag);
    if (!typeName) continue;
    auto type = valueTypeFromName(*typeName);
    if (!type) {
      std::vector<std::string> names;
      for (ValueType t : allValueTypes()) names.emplace_back(valueTypeName(t));
      diag.error(typeNode->loc, attrWhat + ".type: unknown value type " + text::quote(*typeName) + "; known: " +
                                    text::join(names, ", ") + text::didYouMean(*typeName, names));
      continue;
    }
    auto v = readValue(*valueNode, *type, attrWhat, diag);
    if (!v) continue;
    Attribute& a = prim.setAttribute(key.scalar, *v, true);
    a.loc = valueNode->loc;
    if (docNode)
      if (auto doc = readString(*docNode, attrWhat + ".doc", diag)) a.doc = *doc;
  }
}

// Attaches `spec` to `prim` with the values `valueOf(variable)` gives
// (nullptr: not given, the default stays).
void attachBehaviorWithValues(const BehaviorSpec& spec, Prim& prim,
                              const std::function<const RawNode*(const std::string&)>& valueOf, Diagnostics& diag) {
  for (const AttributeSpec& var : spec.variables) {
    const RawNode* valueNode = valueOf(var.name);
    if (!valueNode) continue;
    std::string attrName = exposedAttributeName(spec.name, var.name);
    if (var.locked) {
      diag.error(valueNode->loc, prim.path() + "." + attrName + ": is locked (informational only); remove it");
      continue;
    }
    auto v = readValue(*valueNode, var, prim.path() + "." + attrName, diag);
    if (!v) continue;
    Attribute& a = prim.setAttribute(attrName, *v, true);
    a.doc = var.doc;
    a.loc = valueNode->loc;
  }
  createExposedVariables(prim, spec);
  if (std::find(prim.behaviors().begin(), prim.behaviors().end(), spec.name) == prim.behaviors().end())
    prim.behaviors().push_back(spec.name);
}

void readBehaviors(const RawNode& node, const std::string& what, const BehaviorCatalog& catalog, Prim& prim,
                   Diagnostics& diag) {
  MapReader map(node, what, diag);
  if (!map.ok()) return;
  for (const auto& [key, params] : node.entries) {
    map.allow(key.scalar);
    const BehaviorSpec* spec = catalog.find(key.scalar);
    if (!spec) {
      std::vector<std::string> names = catalog.names();
      std::string suggestion = text::didYouMean(key.scalar, names);
      diag.error(key.loc, prim.path() + ": unknown behavior " + text::quote(key.scalar) + "; known behaviors: " +
                              (names.empty() ? std::string("(none registered)") : text::join(names, ", ")) +
                              (suggestion.empty() ? std::string(text::kScriptNotLoadedHint) : suggestion));
      continue;
    }
    std::string behaviorWhat = prim.path() + " " + spec->name;
    MapReader vars(params, behaviorWhat, diag);
    if (!vars.ok()) continue;
    // `enabled: false` detaches a behavior the prim has (from a referenced
    // asset, say) or keeps one from being attached.
    const auto attached = std::find(prim.behaviors().begin(), prim.behaviors().end(), spec->name);
    if (const RawNode* enabled = vars.get("enabled")) {
      std::optional<Value> on = readValue(*enabled, ValueType::Bool, behaviorWhat + ".enabled", diag);
      if (on && !on->get<bool>()) {
        if (params.entries.size() > 1)
          diag.error(enabled->loc, behaviorWhat + ": switched off with enabled: false, so its other keys would do "
                                                  "nothing; remove them");
        if (attached != prim.behaviors().end()) {
          prim.behaviors().erase(attached);
          removeExposedVariables(prim, *spec);
        }
        continue;
      }
    }
    attachBehaviorWithValues(*spec, prim, [&vars](const std::string& name) { return vars.get(name); }, diag);
    vars.finish();
  }
}

// `omni:scripting:scripts: [files]` on a YAML prim, as on a USD prim: each
// file's behaviors (attached_scripts.h; the loader resolved every listed
// file before the prims are read) with their `exposedVar:<ns>:<name>` keys
// of the same entry as values. Returns the namespaces attached.
std::vector<std::string> readScriptList(const RawNode& entry, const RawNode& list, const std::string& what,
                                        const BehaviorCatalog& catalog, Prim& prim, Diagnostics& diag) {
  std::vector<std::string> attached;
  if (!list.isSequence()) {
    diag.error(list.loc, what + ": expected a list of behavior script files, found " + list.describe());
    return attached;
  }
  for (const RawNode& item : list.items) {
    if (!item.isScalar() || item.scalar.empty()) {
      diag.error(item.loc, what + ": expected a script file path, found " + item.describe());
      continue;
    }
    auto found = catalog.attachedScripts.find(resolveListedScript(item.scalar, item.loc));
    if (found == catalog.attachedScripts.end()) {
      diag.error(item.loc, what + ": " + text::quote(item.scalar) +
                               " was not loaded: omni:scripting:scripts is read on the scene's own prims (in a "
                               "referenced asset, list the script under the asset's scripts: and attach it with "
                               "behaviors:)");
      continue;
    }
    for (const std::string& name : found->second) {
      const BehaviorSpec* spec = catalog.find(name);
      if (!spec) continue;
      attachBehaviorWithValues(*spec, prim, [&entry, &name](const std::string& var) {
        return entry.find(exposedAttributeName(name, var));
      }, diag);
      attached.push_back(name);
    }
  }
  return attached;
}

// The entry's `exposedVar:<ns>:<name>` keys: values of a behavior its
// omni:scripting:scripts attached (read there); anything else is an error.
void checkExposedKeys(const RawNode& entry, const std::vector<std::string>& attached, const BehaviorCatalog& catalog,
                      Prim& prim, MapReader& map, Diagnostics& diag) {
  for (const RawEntry& e : entry.entries) {
    const std::string& key = e.key.scalar;
    if (!key.starts_with("exposedVar:")) continue;
    map.allow(key);
    const std::string rest = key.substr(std::string_view("exposedVar:").size());
    const std::string ns = rest.substr(0, rest.find(':'));
    const std::string var = rest.find(':') == std::string::npos ? "" : rest.substr(rest.find(':') + 1);
    const BehaviorSpec* spec = catalog.find(ns);
    if (std::find(attached.begin(), attached.end(), ns) == attached.end() || !spec) {
      diag.error(e.key.loc, prim.path() + "." + key + ": no script in this prim's omni:scripting:scripts defines " +
                                "the behavior " + text::quote(ns) + " (with behaviors:, give the variable there)");
      continue;
    }
    if (!spec->findVariable(var)) {
      std::vector<std::string> names = spec->variableNames();
      diag.error(e.key.loc, prim.path() + "." + key + ": " + ns + " has no variable " + text::quote(var) +
                                "; its variables: " + text::join(names, ", ") + text::didYouMean(var, names));
    }
  }
}

void readMetadata(const RawNode& node, const std::string& what, Prim& prim, Diagnostics& diag) {
  MapReader map(node, what, diag);
  if (!map.ok()) return;
  for (const auto& [key, value] : node.entries) {
    map.allow(key.scalar);
    if (auto s = readString(value, joinWhat(what, key.scalar), diag)) prim.metadata()[key.scalar] = *s;
  }
}

// Everything of one prim entry but its type (and its reference, mounted
// already). On a prim from a referenced asset the entry's values override
// the asset's: attributes and labels one by one, behaviors variable by
// variable, the transform as a whole (any op key replaces every op).
void fillPrim(const PrimDecl& decl, const BehaviorCatalog& catalog, Prim& prim, Diagnostics& diag) {
  if (!decl.over) prim.loc() = decl.loc;
  bool opsReplaced = !decl.over;
  size_t overrideOps = 0;  // an override's ops so far: they go before a mounted USD prim's units ops
  const RawNode& entry = *decl.entry;
  MapReader map(entry, prim.path(), diag);
  if (!map.ok() || entry.isNull()) return;
  const PrimTypeInfo& info = prim.typeInfo();
  map.allow("type");
  std::vector<std::string> scripted;  // behaviors omni:scripting:scripts attached

  for (const auto& [key, value] : entry.entries) {
    const std::string& name = key.scalar;
    std::string what = prim.path() + "." + name;
    if (std::find(std::begin(kPrimStructuralKeys), std::end(kPrimStructuralKeys), name) !=
        std::end(kPrimStructuralKeys)) {
      map.allow(name);
      if (name == "semantics") readSemantics(value, what, prim, diag);
      else if (name == "material") readMaterialBinding(value, what, prim, diag);
      else if (name == "behaviors") readBehaviors(value, what, catalog, prim, diag);
      else if (name == "attributes") readCustomAttributes(value, what, prim, diag);
      else if (name == "metadata") readMetadata(value, what, prim, diag);
      else if (name == kScriptsKey) scripted = readScriptList(entry, value, what, catalog, prim, diag);
      continue;
    }
    if (const AttributeSpec* spec = findSchemaAttribute(prim.type(), name)) {
      map.allow(name);
      if (auto v = readValue(value, *spec, what, diag)) prim.setAttribute(name, *v).loc = value.loc;
      continue;
    }
    if (auto op = parseXformOpName("xformOp:" + name)) {
      map.allow(name);
      if (!info.xformable) {
        diag.error(key.loc, what + ": " + std::string(info.name) + " prims have no transform");
        continue;
      }
      if (!op->suffix.empty() && !isValidAttributeName(op->suffix)) {
        diag.error(key.loc, what + ": the op suffix must be an identifier");
        continue;
      }
      if (auto v = readValue(value, xformOpValueType(op->kind), what, diag)) {
        op->value = *v;
        if (op->kind == XformOpKind::Orient && v->get<Quatd>().norm() < 1e-12) {
          diag.error(value.loc, what + ": the quaternion must not be zero");
          continue;
        }
        if (!opsReplaced) {
          // The override's ops replace the asset's, but not the units
          // correction of a USD asset mounted here (usd_import.h), which
          // stays after them as Omniverse's unitsResolve ops do.
          std::erase_if(prim.xformOps(), [](const XformOp& o) { return o.suffix != kUnitsResolveSuffix; });
          opsReplaced = true;
        }
        if (decl.over) prim.xformOps().insert(prim.xformOps().begin() + std::ptrdiff_t(overrideOps++), std::move(*op));
        else prim.xformOps().push_back(std::move(*op));
      }
      continue;
    }
  }
  checkExposedKeys(entry, scripted, catalog, prim, map, diag);
  // Unknown keys: suggest among everything this prim type accepts.
  for (const AttributeSpec& spec : info.attributes) map.allow(spec.name);
  if (info.xformable)
    for (XformOpKind kind : allXformOpKinds()) map.allow(xformOpKindName(kind));
  map.finish();
}

}  // namespace

bool isValidAttributeName(std::string_view name) {
  if (name.empty() || name.size() > 1024) return false;
  size_t start = 0;
  while (true) {
    size_t colon = name.find(':', start);
    if (!path::isIdentifier(name.substr(start, colon == std::string_view::npos ? colon : colon - start)))
      return false;
    if (colon == std::string_view::npos) return true;
    start = colon + 1;
  }
}

void readPrims(const RawNode& prims, const BehaviorCatalog& catalog, Stage& stage, Diagnostics& diag,
               const PrimReferences& references) {
  if (prims.isNull()) return;  // a scene with no prims yet
  if (!prims.isMap()) {
    diag.error(prims.loc, "prims: expected a mapping from prim path to prim, found " + prims.describe());
    return;
  }
  // Pass 1: paths and types.
  std::vector<PrimDecl> decls;
  std::unordered_map<std::string_view, const PrimDecl*> byPath;
  decls.reserve(prims.entries.size());
  for (const auto& [key, entry] : prims.entries) {
    if (!key.isScalar()) {
      diag.error(key.loc, "prims: a prim path must be a string, found " + key.describe());
      continue;
    }
    if (std::string why = path::whyInvalid(key.scalar); !why.empty()) {
      diag.error(key.loc, "prims: " + text::quote(key.scalar) + " is not a valid prim path: " + why);
      continue;
    }
    PrimDecl decl;
    decl.path = key.scalar;
    decl.entry = &entry;
    decl.loc = key.loc;
    if (!entry.isMap() && !entry.isNull()) {
      diag.error(entry.loc, key.scalar + ": expected a mapping (the prim's type and attributes), found " +
                                entry.describe());
      continue;
    }
    if (const RawNode* typeNode = entry.isMap() ? entry.find("type") : nullptr) {
      auto typeName = readString(*typeNode, key.scalar + ".type", diag);
      if (!typeName) continue;
      auto type = primTypeFromName(*typeName);
      if (!type) {
        std::vector<std::string> names = primTypeNames();
        diag.error(typeNode->loc, key.scalar + ".type: unknown prim type " + text::quote(*typeName) +
                                      "; known types: " + text::join(names, ", ") +
                                      text::didYouMean(*typeName, names));
        continue;
      }
      decl.type = *type;
      decl.typeNode = typeNode;
    }
    if (const RawNode* refNode = entry.isMap() ? entry.find("reference") : nullptr) {
      if (decl.typeNode) {
        diag.error(decl.typeNode->loc, key.scalar + ".type: a prim with reference: takes its type from the asset; "
                                                    "remove type:");
        continue;
      }
      decl.reference = readReferenceSpec(*refNode, key.scalar + ".reference", diag);
      if (!decl.reference) continue;
      if (!references.library) {
        diag.error(refNode->loc, key.scalar + ".reference: references cannot be used here");
        continue;
      }
    }
    decls.push_back(std::move(decl));
  }
  for (const PrimDecl& decl : decls) {
    auto [it, inserted] = byPath.emplace(decl.path, &decl);
    if (!inserted)
      diag.error(decl.loc, "prims: duplicate prim path " + decl.path + " (first defined at line " +
                               std::to_string(it->second->loc.line) + ")");
  }
  // Pass 2: define parents before children (siblings in document order),
  // mounting referenced assets as their prims come; every parent must be
  // listed or mounted.
  std::vector<PrimDecl*> ordered;
  for (PrimDecl& decl : decls)
    if (byPath.at(decl.path) == &decl) ordered.push_back(&decl);  // a duplicate was reported
  std::stable_sort(ordered.begin(), ordered.end(), [](const PrimDecl* a, const PrimDecl* b) {
    return path::depth(a->path) < path::depth(b->path);
  });
  for (PrimDecl* decl : ordered) {
    std::string_view parent = path::parent(decl->path);
    if (parent != "/" && !stage.find(parent)) {
      if (!byPath.count(parent))  // a listed parent that failed was reported already
        diag.error(decl->loc, decl->path + ": its parent " + std::string(parent) +
                                  " is not defined; add it to prims (e.g. `" + std::string(parent) +
                                  ": {type: Xform}`): sdgbehave does not create parents implicitly");
      continue;
    }
    if (const Prim* mounted = stage.find(decl->path)) {
      // Mounted from an ancestor's reference: this entry overrides it.
      if (decl->reference) {
        diag.error(decl->reference->loc, decl->path + ".reference: the prim comes from the asset referenced by an "
                                                      "ancestor; put the reference on a prim of its own");
        continue;
      }
      if (decl->typeNode && decl->type != mounted->type()) {
        diag.error(decl->typeNode->loc, decl->path + ".type: the referenced asset makes it a " +
                                            std::string(mounted->typeInfo().name) +
                                            "; an override cannot change a prim's type");
        continue;
      }
      decl->over = decl->defined = true;
      continue;
    }
    if (decl->reference) {
      references.library->mount(*decl->reference, references.fromDir, decl->path, stage, catalog, diag);
      decl->over = decl->defined = stage.find(decl->path) != nullptr;
      continue;
    }
    stage.definePrim(decl->path, decl->type);
    decl->defined = true;
  }
  if (diag.hasErrors()) return;
  // Pass 3: fill in document order.
  for (const PrimDecl& decl : decls)
    if (decl.defined) fillPrim(decl, catalog, *stage.find(decl.path), diag);
}

}  // namespace sdg
