#include "scene_io/overrides.h"

#include "core/text.h"
#include "scene_io/raw_node.h"
#include "scene_io/yaml_events.h"
#include "scene_io/value_reader.h"
#include "stage/path.h"

namespace sdg {
namespace {

struct Override {
  std::string label;  // "--set[1]"
  std::string target;
  RawNode value;
  SourceLoc targetLoc;
};

// The spec an existing attribute is checked against: the behavior's variable
// spec for exposed variables, else one built from the value's type.
AttributeSpec specForExisting(const Prim& prim, const std::string& name, const Attribute& attribute,
                              const BehaviorCatalog& catalog) {
  for (const std::string& behavior : prim.behaviors())
    if (const BehaviorSpec* spec = catalog.find(behavior))
      for (const AttributeSpec& var : spec->variables)
        if (exposedAttributeName(behavior, var.name) == name) return var;
  AttributeSpec spec;
  spec.name = name;
  spec.type = attribute.value.type();
  return spec;
}

void applyToPrim(const Override& o, const BehaviorCatalog& catalog, Scene& scene, Diagnostics& diag) {
  size_t dot = o.target.find('.');
  std::string primPath = o.target.substr(0, dot);
  if (dot == std::string::npos) {
    diag.error(o.targetLoc, o.label + ": expected PRIM_PATH.ATTRIBUTE=VALUE, found no attribute after " + primPath);
    return;
  }
  std::string name = o.target.substr(dot + 1);
  Prim* prim = scene.stage.find(primPath);
  if (!prim) {
    std::string why = path::whyInvalid(primPath);
    diag.error(o.targetLoc, o.label + ": prim " + primPath + (why.empty() ? " does not exist" : " is not a valid path: " + why));
    return;
  }
  std::string what = primPath + "." + name;
  SourceLoc attrLoc{o.targetLoc.file, 1, o.targetLoc.column + static_cast<int>(dot) + 1};

  if (const AttributeSpec* spec = findSchemaAttribute(prim->type(), name)) {
    if (auto v = readValue(o.value, *spec, what, diag)) prim->setAttribute(name, *v).loc = o.value.loc;
    return;
  }
  if (Attribute* existing = prim->findAttribute(name)) {
    AttributeSpec spec = specForExisting(*prim, name, *existing, catalog);
    if (spec.locked) {
      diag.error(attrLoc, what + ": is locked (informational only)");
      return;
    }
    if (auto v = readValue(o.value, spec, what, diag)) {
      existing->value = *v;
      existing->loc = o.value.loc;
    }
    return;
  }
  std::string opName = name.rfind("xformOp:", 0) == 0 ? name : "xformOp:" + name;
  if (parseXformOpName(opName)) {
    XformOp* op = prim->findXformOp(opName);
    if (!op) {
      diag.error(attrLoc, what + ": the prim has no " + opName + " op; add it in the scene (--set only changes values)");
      return;
    }
    if (auto v = readValue(o.value, xformOpValueType(op->kind), what, diag)) op->value = *v;
    return;
  }
  std::vector<std::string> candidates;
  for (const AttributeSpec& spec : prim->typeInfo().attributes) candidates.push_back(spec.name);
  for (const auto& [attrName, attribute] : prim->attributes()) candidates.push_back(attrName);
  for (const XformOp& op : prim->xformOps()) candidates.push_back(op.attributeName());
  diag.error(attrLoc, what + ": " + std::string(prim->typeInfo().name) + " prim " + primPath +
                          " has no attribute " + text::quote(name) + text::didYouMean(name, candidates));
}

bool applyToOptions(const Override& o, std::string_view section, std::string_view key,
                    std::span<const AttributeSpec> specs, OptionSet& options, Diagnostics& diag) {
  for (const AttributeSpec& spec : specs) {
    if (spec.name != key) continue;
    if (auto v = readValue(o.value, spec, o.target, diag)) options.set(spec.name, *v, o.value.loc);
    return true;
  }
  std::vector<std::string> names;
  for (const AttributeSpec& spec : specs) names.push_back(spec.name);
  diag.error(o.targetLoc, o.label + ": " + std::string(section) + " has no option " + text::quote(key) +
                              text::didYouMean(key, names));
  return false;
}

void applyToSettings(const Override& o, Scene& scene, Diagnostics& diag) {
  size_t dot = o.target.find('.');
  std::string section = o.target.substr(0, dot);
  std::string key = dot == std::string::npos ? "" : o.target.substr(dot + 1);
  if (section == "render") {
    applyToOptions(o, section, key, renderOptionSpecs(), scene.render, diag);
  } else if (section == "physics") {
    applyToOptions(o, section, key, physicsOptionSpecs(), scene.physics, diag);
  } else if (section == "run") {
    applyToOptions(o, section, key, runOptionSpecs(), scene.run, diag);
  } else if (section == "capture") {
    applyToOptions(o, section, key, captureOptionSpecs(), scene.capture, diag);
  } else if (section == "stage") {
    OptionSet options(stageOptionSpecs());
    if (applyToOptions(o, section, key, stageOptionSpecs(), options, diag) && options.isAuthored(key)) {
      if (key == "timeCodesPerSecond") scene.stage.metadata().timeCodesPerSecond = options.get(key).get<double>();
      if (key == "metersPerUnit") scene.stage.metadata().metersPerUnit = options.get(key).get<double>();
      if (key == "upAxis") scene.stage.metadata().upAxis = options.getString(key);
    }
  } else if (section == "writer") {
    // writer.OPTION with one writer, writer.TYPE.OPTION to pick one.
    WriterConfig* writer = nullptr;
    size_t typeDot = key.find('.');
    if (typeDot != std::string::npos) {
      std::string type = key.substr(0, typeDot);
      for (WriterConfig& w : scene.writers)
        if (w.type == type) writer = &w;
      if (!writer) {
        diag.error(o.targetLoc, o.label + ": the scene has no " + type + " writer");
        return;
      }
      key = key.substr(typeDot + 1);
    } else if (scene.writers.size() == 1) {
      writer = &scene.writers.front();
    } else {
      diag.error(o.targetLoc, o.label + ": the scene has " + std::to_string(scene.writers.size()) +
                                  " writers; name one: writer.<type>.<option>");
      return;
    }
    applyToOptions(o, "writer " + writer->type, key, findWriterType(writer->type)->options, writer->options, diag);
  } else {
    std::vector<std::string> sections = {"render", "capture", "physics", "run", "stage", "writer"};
    diag.error(o.targetLoc, o.label + ": unknown target " + text::quote(o.target) +
                                "; expected /PRIM/PATH.ATTRIBUTE or one of render.*, capture.*, physics.*, run.*, stage.*, writer.*" +
                                text::didYouMean(section, sections));
  }
}

// PRIM.variants:SET: a variant selection (variantSelections).
bool isVariantTarget(const std::string& target) {
  if (target.empty() || target[0] != '/') return false;
  const size_t dot = target.find('.');
  return dot != std::string::npos && target.compare(dot + 1, std::string_view(kVariantsPrefix).size(), kVariantsPrefix) == 0;
}

}  // namespace

std::vector<VariantSelection> variantSelections(std::span<const std::string> overrides, Diagnostics& diag) {
  std::vector<VariantSelection> out;
  for (size_t i = 0; i < overrides.size(); ++i) {
    const std::string& text = overrides[i];
    const size_t equals = text.find('=');
    if (equals == std::string::npos || !isVariantTarget(text.substr(0, equals))) continue;
    const std::string label = "--set[" + std::to_string(i + 1) + "]";
    VariantSelection v;
    v.loc = SourceLoc{label, 1, 1};
    const size_t dot = text.find('.');
    v.prim = text.substr(0, dot);
    v.set = text.substr(dot + 1 + std::string(kVariantsPrefix).size(), equals - dot - 1 - std::string(kVariantsPrefix).size());
    v.variant = text.substr(equals + 1);
    if (std::string why = path::whyInvalid(v.prim); !why.empty()) {
      diag.error(v.loc, label + ": " + v.prim + " is not a valid prim path: " + why);
      continue;
    }
    if (v.set.empty() || v.variant.empty()) {
      diag.error(v.loc, label + ": expected PRIM.variants:SET=VARIANT (e.g. /World/Chair.variants:color=red), found " +
                            text::quote(text));
      continue;
    }
    out.push_back(std::move(v));
  }
  return out;
}

void applyOverrides(std::span<const std::string> overrides, const BehaviorCatalog& catalog, Scene& scene,
                    Diagnostics& diag) {
  for (size_t i = 0; i < overrides.size(); ++i) {
    const std::string& text = overrides[i];
    Override o;
    o.label = "--set[" + std::to_string(i + 1) + "]";
    o.targetLoc = SourceLoc{o.label, 1, 1};
    size_t equals = text.find('=');
    if (equals == std::string::npos || equals == 0) {
      diag.error(o.targetLoc, o.label + ": expected TARGET=VALUE (e.g. render.resolution=[640,480]), found " +
                                  text::quote(text));
      continue;
    }
    o.target = text.substr(0, equals);
    if (isVariantTarget(o.target)) continue;  // composition's (variantSelections)
    try {
      o.value = parseYaml(std::string_view(text).substr(equals + 1), o.label, 0, static_cast<int>(equals) + 1);
    } catch (const SceneError& e) {
      for (const Diagnostic& d : e.problems()) diag.error(d.loc, d.message);
      continue;
    }
    if (o.target[0] == '/') applyToPrim(o, catalog, scene, diag);
    else applyToSettings(o, scene, diag);
  }
  // The scene's own values (its entries for a mounted USD file's prims, and
  // --set) are stronger opinions than the file's time samples.
  scene.stage.animation().dropOverridden(scene.stage);
}

}  // namespace sdg
