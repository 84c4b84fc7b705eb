#include "scene_io/json_schema.h"

#include <cstdlib>
#include <limits>

#include <nlohmann/json.hpp>

#include "core/text.h"
#include "scene_io/prim_reader.h"
#include "stage/value_json.h"
#include "scene_io/scene.h"
#include "stage/xform.h"

namespace sdg {
namespace {

using Json = nlohmann::ordered_json;

constexpr const char* kIdentifierPattern = "[A-Za-z_][A-Za-z0-9_]*";
// A variable's name: identifiers joined by ':' (the rule script variables follow).
constexpr const char* kAttributeNamePattern = "^[A-Za-z_][A-Za-z0-9_]*(:[A-Za-z_][A-Za-z0-9_]*)*$";

Json numbers(size_t count, const char* itemType = "number") {
  return Json{{"type", "array"}, {"items", {{"type", itemType}}}, {"minItems", count}, {"maxItems", count}};
}

Json typeSchema(ValueType type) {
  switch (type) {
    case ValueType::Bool: return {{"type", "boolean"}};
    case ValueType::Int:
      return {{"type", "integer"},
              {"minimum", std::numeric_limits<int32_t>::min()},
              {"maximum", std::numeric_limits<int32_t>::max()}};
    case ValueType::UInt:
      return {{"type", "integer"}, {"minimum", 0}, {"maximum", std::numeric_limits<uint32_t>::max()}};
    case ValueType::Float:
    case ValueType::Double: return {{"type", "number"}};
    case ValueType::Int2: return numbers(2, "integer");
    case ValueType::Float2: return numbers(2);
    case ValueType::Float3:
    case ValueType::Color3f:
    case ValueType::Double3:
    case ValueType::Vector3d: return numbers(3);
    case ValueType::Quatf:
    case ValueType::Quatd: return numbers(4);
    case ValueType::Matrix4d:
      return {{"type", "array"}, {"items", numbers(4)}, {"minItems", 4}, {"maxItems", 4}};
    case ValueType::String:
    case ValueType::Token:
    case ValueType::Asset: return {{"type", "string"}};
    case ValueType::AssetArray:
    case ValueType::StringArray: return {{"type", "array"}, {"items", {{"type", "string"}}}};
    case ValueType::IntArray: return {{"type", "array"}, {"items", {{"type", "integer"}}}};
    case ValueType::FloatArray: return {{"type", "array"}, {"items", {{"type", "number"}}}};
    case ValueType::Point3fArray:
    case ValueType::Normal3fArray:
    case ValueType::Color3fArray: return {{"type", "array"}, {"items", numbers(3)}};
    case ValueType::TexCoord2fArray: return {{"type", "array"}, {"items", numbers(2)}};
  }
  return {};
}

Json attributeSchema(const AttributeSpec& spec) {
  Json s;
  if (!spec.doc.empty()) s["description"] = spec.doc;
  Json t = typeSchema(spec.type);
  for (auto& [k, v] : t.items()) s[k] = v;
  if (!spec.allowedTokens.empty()) {
    s["enum"] = spec.allowedTokens;
    // A token that is a whole number (render.subdivision_level: none, 1, 2,
    // ...) reads from YAML written bare too: the schema takes both spellings.
    for (const std::string& token : spec.allowedTokens)
      if (!token.empty() && token.find_first_not_of("0123456789") == std::string::npos) {
        s["type"] = Json::array({"string", "integer"});
        s["enum"].push_back(std::stoi(token));
      }
  }
  if (spec.minimum) {
    if (s["type"] == "array" && s["items"].is_object()) s["items"]["minimum"] = *spec.minimum;
    else s["minimum"] = *spec.minimum;
  }
  s["default"] = valueToJson(spec.defaultValue);
  return s;
}

Json optionsObject(std::span<const AttributeSpec> specs, const char* description) {
  Json props = Json::object();
  for (const AttributeSpec& spec : specs) props[spec.name] = attributeSchema(spec);
  return {{"description", description}, {"type", {"object", "null"}}, {"additionalProperties", false}, {"properties", props}};
}

Json writerSchema() {
  Json variants = Json::array();
  for (const WriterTypeInfo& type : writerTypes()) {
    Json props = Json::object();
    props["type"] = {{"const", type.name}};
    for (const AttributeSpec& spec : type.options) props[spec.name] = attributeSchema(spec);
    variants.push_back({{"description", type.doc},
                        {"type", "object"},
                        {"required", {"type"}},
                        {"additionalProperties", false},
                        {"properties", props}});
  }
  return {{"oneOf", variants}};
}

Json payloadSchema() {
  return {{"type", "object"}, {"additionalProperties", {{"type", {"string", "number", "boolean"}}}}};
}

Json eventsSchema() {
  Json step = {{"type", "object"},
               {"required", {"publish"}},
               {"additionalProperties", false},
               {"properties",
                {{"publish", {{"type", "string"}, {"description", "Event to publish."}}},
                 {"payload", {{"$ref", "#/definitions/payload"}}},
                 {"wait_event",
                  {{"type", "string"}, {"description", "Event to wait on; defaults to publish with .in replaced by .out."}}},
                 {"wait_for", {{"$ref", "#/definitions/payload"}, {"description", "Entries the reply must contain."}}},
                 {"max_updates", {{"type", "integer"}, {"minimum", 1}, {"description", "Updates to wait at most."}}}}}};
  return {{"description", "The pre-roll: publish each event, then wait for its reply."},
          {"type", "array"},
          {"items", step}};
}

Json enabledSchema() {
  return {{"description", "false detaches the behavior (one a referenced asset attached, say)."}, {"type", "boolean"}};
}

Json behaviorsSchema(const BehaviorCatalog& catalog) {
  Json props = Json::object();
  for (const BehaviorSpec& spec : catalog.specs) {
    Json vars = Json::object();
    for (const AttributeSpec& var : spec.variables)
      if (!var.locked) vars[var.name] = attributeSchema(var);
    vars["enabled"] = enabledSchema();
    props[spec.name] = {{"description", spec.summary},
                        {"type", {"object", "null"}},
                        {"additionalProperties", false},
                        {"properties", vars}};
  }
  // A behavior this schema does not know comes from a script or plugin the
  // scene loads (`scripts:`, `plugins:`), which the committed schema cannot
  // see: it is accepted with loosely typed variables, so an editor does not
  // underline a valid scene; `sdgbehave schema --script/--plugin` types it,
  // and the loader checks every name and value (with did-you-mean).
  Json unknown = {{"description", "A behavior defined by a behavior script or plugin the scene loads; "
                                  "`sdgbehave schema --script FILE.py` (or --plugin) lists its variables."},
                  {"type", {"object", "null"}},
                  {"propertyNames", {{"pattern", kAttributeNamePattern}}},
                  {"properties", {{"enabled", enabledSchema()}}}};
  return {{"description", "Behaviors attached to the prim, in order, with their exposed variables."},
          {"type", "object"},
          {"additionalProperties", unknown},
          {"properties", props}};
}

Json primSchema(const PrimTypeInfo& info) {
  Json props = Json::object();
  props["type"] = {{"const", info.name}};
  for (const AttributeSpec& spec : info.attributes) props[spec.name] = attributeSchema(spec);
  props["semantics"] = {{"$ref", "#/definitions/semantics"}};
  props["material"] = {{"$ref", "#/definitions/material"}};
  props["behaviors"] = {{"$ref", "#/definitions/behaviors"}};
  props["attributes"] = {{"$ref", "#/definitions/attributes"}};
  props["metadata"] = {{"type", "object"}, {"additionalProperties", {{"type", "string"}}}};
  Json s = {{"description", info.doc}, {"type", "object"}, {"additionalProperties", false}, {"properties", props}};
  if (info.xformable) {
    Json patterns = Json::object();
    for (XformOpKind kind : allXformOpKinds()) {
      std::string pattern = "^" + std::string(xformOpKindName(kind)) + "(:" + kIdentifierPattern + ")*$";
      Json op = typeSchema(xformOpValueType(kind));
      op["description"] = "xformOp:" + std::string(xformOpKindName(kind)) + "; ops apply in the order written";
      patterns[pattern] = op;
    }
    s["patternProperties"] = patterns;
  }
  // Xform is the default type: its entries may omit `type`.
  if (info.type != PrimType::Xform) s["required"] = {"type"};
  return s;
}

// Isaac's way of attaching scripts on a prim: `omni:scripting:scripts`
// (files) and each behavior's variables as `exposedVar:<ns>:<name>` keys
// (one definition per variable, referenced from every prim type).
void addScriptKeys(Json& primDef, const BehaviorCatalog& catalog) {
  Json& props = primDef["properties"];
  props["omni:scripting:scripts"] = {
      {"description", "Behavior script files, as Isaac Sim attaches them (docs/isaac-scripts.md); their variables "
                      "are this prim's exposedVar:<behavior>:<name> keys."},
      {"type", "array"},
      {"items", {{"type", "string"}, {"minLength", 1}}}};
  for (const BehaviorSpec& spec : catalog.specs)
    for (const AttributeSpec& var : spec.variables)
      if (!var.locked) {
        const std::string name = exposedAttributeName(spec.name, var.name);
        props[name] = {{"$ref", "#/definitions/" + name}};
      }
}

void addExposedVariableDefs(Json& defs, const BehaviorCatalog& catalog) {
  for (const BehaviorSpec& spec : catalog.specs)
    for (const AttributeSpec& var : spec.variables)
      if (!var.locked) defs[exposedAttributeName(spec.name, var.name)] = attributeSchema(var);
}

}  // namespace

std::string sceneJsonSchema(const BehaviorCatalog& catalog) {
  Json defs = Json::object();
  Json primVariants = Json::array({{{"type", "null"}}});
  for (const PrimTypeInfo& info : allPrimTypes()) {
    std::string name = "prim" + std::string(info.name);
    defs[name] = primSchema(info);
    addScriptKeys(defs[name], catalog);
    primVariants.push_back({{"$ref", "#/definitions/" + name}});
  }
  // A prim that mounts a smart asset: its type (and so which attributes it
  // has) comes from the asset, which JSON Schema cannot see.
  Json referenceValue = {{"oneOf", Json::array({{{"type", "string"}, {"minLength", 1}},
                                                {{"type", "object"},
                                                 {"additionalProperties", false},
                                                 {"required", {"file"}},
                                                 {"properties", {{"file", {{"type", "string"}}},
                                                                 {"prim", {{"type", "string"}}}}}}})}};
  defs["primReference"] = {
      {"description", "A prim that mounts the prim tree of a smart asset (another scene file) at its path; its "
                      "other keys override the asset's values."},
      {"type", "object"},
      {"required", {"reference"}},
      {"not", {{"required", {"type"}}}},
      {"properties", {{"reference", referenceValue},
                      {"semantics", {{"$ref", "#/definitions/semantics"}}},
                      {"material", {{"$ref", "#/definitions/material"}}},
                      {"behaviors", {{"$ref", "#/definitions/behaviors"}}},
                      {"attributes", {{"$ref", "#/definitions/attributes"}}},
                      {"metadata", {{"type", "object"}, {"additionalProperties", {{"type", "string"}}}}}}}};
  addScriptKeys(defs["primReference"], catalog);
  addExposedVariableDefs(defs, catalog);
  primVariants.push_back({{"$ref", "#/definitions/primReference"}});
  defs["prim"] = {{"oneOf", primVariants}};
  defs["writer"] = writerSchema();
  defs["payload"] = payloadSchema();
  defs["behaviors"] = behaviorsSchema(catalog);
  Json label = {{"type", "string"}, {"minLength", 1}};
  Json labels = {{"type", "array"}, {"items", label}};
  Json oneOrMany = Json::object();
  oneOrMany["oneOf"] = Json::array({label, labels});
  defs["semantics"] = {{"description", "Labels per taxonomy, e.g. {class: power_drill}."},
                       {"type", "object"},
                       {"propertyNames", {{"pattern", std::string("^") + kIdentifierPattern + "$"}}},
                       {"additionalProperties", oneOrMany}};
  defs["material"] = {
      {"description", "Material binding: a Material prim path, or {path, strength}."},
      {"oneOf",
       {{{"type", "string"}},
        {{"type", "object"},
         {"required", {"path"}},
         {"additionalProperties", false},
         {"properties",
          {{"path", {{"type", "string"}}},
           {"strength", {{"enum", {"weakerThanDescendants", "strongerThanDescendants"}}}}}}}}}};
  Json typeNames = Json::array();
  for (ValueType t : allValueTypes()) typeNames.push_back(valueTypeName(t));
  defs["attributes"] = {
      {"description", "Custom typed attributes: name -> {type, value, doc}."},
      {"type", "object"},
      {"additionalProperties",
       {{"type", "object"},
        {"required", {"type", "value"}},
        {"additionalProperties", false},
        {"properties", {{"type", {{"enum", typeNames}}}, {"value", Json::object()}, {"doc", {{"type", "string"}}}}}}}};

  Json props = Json::object();
  props["version"] = {{"const", kSceneFormatVersion}, {"description", "Scene format version."}};
  props["stage"] = optionsObject(stageOptionSpecs(), "Stage-wide metadata (USD names).");
  props["asset_roots"] = {{"description", "Folders searched for assets, relative to the scene file."},
                          {"type", "array"},
                          {"items", {{"type", "string"}}}};
  props["plugins"] = {{"description", "Behavior plugin libraries (.so) to load before the prims are read."},
                      {"type", "array"},
                      {"items", {{"type", "string"}}}};
  props["scripts"] = {{"description", "Behavior scripts (Python files), relative to the scene file; loading the scene "
                                      "runs their top-level code."},
                      {"type", "array"},
                      {"items", {{"type", "string"}}}};
  props["isaac_assets"] = {{"description", "A local copy of Isaac Sim's asset pack (the folder holding Isaac/), relative "
                                           "to the scene file; /Isaac/... paths resolve below it."},
                           {"type", "string"}};
  props["render"] = optionsObject(renderOptionSpecs(), "Rendering settings.");
  props["physics"] = optionsObject(physicsOptionSpecs(), "Rigid-body settings of the stacking simulation.");
  props["capture"] = optionsObject(captureOptionSpecs(), "What to capture.");
  props["run"] = optionsObject(runOptionSpecs(), "How the run guards itself against behavior scripts that hang.");
  props["writer"] = {{"description", "One writer, or a list of writers of different types."},
                     {"oneOf", {{{"$ref", "#/definitions/writer"}},
                                {{"type", "array"}, {"items", {{"$ref", "#/definitions/writer"}}}}}}};
  props["events"] = eventsSchema();
  props["prims"] = {{"description", "Prims by absolute path; a prim's parent must be listed too."},
                    {"type", {"object", "null"}},
                    {"propertyNames", {{"pattern", std::string("^(/") + kIdentifierPattern + ")+$"}}},
                    {"additionalProperties", {{"$ref", "#/definitions/prim"}}}};

  Json schema = {{"$schema", "http://json-schema.org/draft-07/schema#"},
                 {"$comment", "Generated by `sdgbehave schema`; do not edit by hand."},
                 {"title", "sdgbehave scene"},
                 {"type", "object"},
                 {"required", {"version", "prims"}},
                 {"additionalProperties", false},
                 {"properties", props},
                 {"definitions", defs}};
  return schema.dump(2) + "\n";
}

}  // namespace sdg
