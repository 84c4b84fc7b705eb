#include "scene_io/scene_loader.h"

#include <filesystem>
#include <memory>

#include "core/text.h"
#include "scene_io/map_reader.h"
#include "scene_io/overrides.h"
#include "scene_io/prim_reader.h"
#include "scene_io/references.h"
#include "scene_io/scene_validate.h"
#include "scene_io/usd_mesh_asset.h"
#include "scene_io/value_reader.h"
#include "scene_io/yaml_events.h"

namespace sdg {
namespace {

void readOptions(MapReader& section, std::span<const AttributeSpec> specs, OptionSet& into, Diagnostics& diag) {
  for (const AttributeSpec& spec : specs) {
    const RawNode* node = section.get(spec.name);
    if (!node) continue;
    if (auto v = readValue(*node, spec, joinWhat(section.what(), spec.name), diag)) into.set(spec.name, *v, node->loc);
  }
  section.finish();
}

void readStageSection(const RawNode& node, Stage& stage, Diagnostics& diag) {
  OptionSet options(stageOptionSpecs());
  MapReader section(node, "stage", diag);
  readOptions(section, stageOptionSpecs(), options, diag);
  stage.metadata().timeCodesPerSecond = options.get("timeCodesPerSecond").get<double>();
  stage.metadata().metersPerUnit = options.get("metersPerUnit").get<double>();
  stage.metadata().upAxis = options.getString("upAxis");
}

void readWriter(const RawNode& node, std::string what, Scene& scene, Diagnostics& diag) {
  MapReader writer(node, what, diag);
  if (!writer.ok()) return;
  const RawNode* typeNode = writer.require("type");
  if (!typeNode) return;
  auto typeName = readString(*typeNode, joinWhat(what, "type"), diag);
  if (!typeName) return;
  const WriterTypeInfo* type = findWriterType(*typeName);
  if (!type) {
    std::vector<std::string> names;
    for (const WriterTypeInfo& t : writerTypes()) names.emplace_back(t.name);
    diag.error(typeNode->loc, joinWhat(what, "type") + ": unknown writer " + text::quote(*typeName) +
                                  "; known writers: " + text::join(names, ", ") + text::didYouMean(*typeName, names));
    return;
  }
  for (const WriterConfig& existing : scene.writers)
    if (existing.type == type->name) {
      diag.error(typeNode->loc, what + ": a second " + *typeName + "; each writer type may appear once");
      return;
    }
  WriterConfig config{std::string(type->name), OptionSet(type->options), node.loc};
  readOptions(writer, type->options, config.options, diag);
  scene.writers.push_back(std::move(config));
}

void readWriters(const RawNode& node, Scene& scene, Diagnostics& diag) {
  if (node.isSequence()) {
    for (size_t i = 0; i < node.items.size(); ++i)
      readWriter(node.items[i], "writer[" + std::to_string(i) + "]", scene, diag);
  } else {
    readWriter(node, "writer", scene, diag);
  }
}

std::optional<Payload> readPayload(const RawNode& node, const std::string& what, Diagnostics& diag) {
  MapReader map(node, what, diag);
  if (!map.ok()) return std::nullopt;
  Payload payload;
  for (const auto& [key, value] : node.entries) {
    map.allow(key.scalar);
    std::string keyWhat = joinWhat(what, key.scalar);
    if (!value.isScalar()) {
      diag.error(value.loc, keyWhat + ": expected a string, number or bool, found " + value.describe());
      continue;
    }
    Diagnostics notANumber;  // a scalar that is not a number is a string
    std::optional<Value> number;
    if (!value.quoted) number = readValue(value, ValueType::Double, keyWhat, notANumber);
    if (!value.quoted && (value.scalar == "true" || value.scalar == "false")) {
      payload.set(key.scalar, value.scalar == "true");
    } else if (number) {
      payload.set(key.scalar, number->get<double>());
    } else {
      payload.set(key.scalar, value.scalar);
    }
  }
  return payload;
}

void readEvents(const RawNode& node, Scene& scene, Diagnostics& diag) {
  if (!node.isSequence()) {
    diag.error(node.loc, "events: expected a list of steps, found " + node.describe());
    return;
  }
  for (size_t i = 0; i < node.items.size(); ++i) {
    std::string what = "events[" + std::to_string(i) + "]";
    MapReader step(node.items[i], what, diag);
    if (!step.ok()) continue;
    EventStep event;
    event.loc = node.items[i].loc;
    if (const RawNode* n = step.require("publish"))
      if (auto s = readString(*n, joinWhat(what, "publish"), diag)) event.publish = *s;
    if (const RawNode* n = step.get("payload"))
      if (auto p = readPayload(*n, joinWhat(what, "payload"), diag)) event.payload = *p;
    if (const RawNode* n = step.get("wait_event")) {
      if (auto s = readString(*n, joinWhat(what, "wait_event"), diag)) event.waitEvent = *s;
    } else if (event.publish.size() > 3 && event.publish.ends_with(".in")) {
      event.waitEvent = event.publish.substr(0, event.publish.size() - 3) + ".out";
    }
    if (const RawNode* n = step.get("wait_for"))
      if (auto p = readPayload(*n, joinWhat(what, "wait_for"), diag)) event.waitFor = *p;
    if (const RawNode* n = step.get("max_updates")) {
      AttributeSpec spec;
      spec.type = ValueType::UInt;
      spec.minimum = 1;
      if (auto v = readValue(*n, spec, joinWhat(what, "max_updates"), diag)) event.maxUpdates = v->get<uint32_t>();
    }
    step.finish();
    if (!event.waitFor.empty() && event.waitEvent.empty())
      diag.error(event.loc, what + ": wait_for needs wait_event (the event to listen on), since " +
                                text::quote(event.publish) + " does not end in '.in'");
    scene.events.push_back(std::move(event));
  }
}

std::vector<std::string> readStringList(const RawNode& node, const std::string& what, Diagnostics& diag) {
  if (auto v = readValue(node, ValueType::StringArray, what, diag)) return v->get<std::vector<std::string>>();
  return {};
}

}  // namespace

void readSettingSections(MapReader& top, Scene& scene, Diagnostics& diag) {
  const struct {
    const char* name;
    std::span<const AttributeSpec> specs;
    OptionSet& into;
  } sections[] = {{"render", renderOptionSpecs(), scene.render},
                  {"physics", physicsOptionSpecs(), scene.physics},
                  {"capture", captureOptionSpecs(), scene.capture},
                  {"run", runOptionSpecs(), scene.run}};
  for (const auto& s : sections)
    if (const RawNode* n = top.get(s.name)) {
      MapReader section(*n, s.name, diag);
      readOptions(section, s.specs, s.into, diag);
    }
  if (const RawNode* n = top.get("writer")) readWriters(*n, scene, diag);
  if (const RawNode* n = top.get("events")) readEvents(*n, scene, diag);
}

Scene buildScene(const SceneDocument& doc, const BehaviorCatalog& catalog, std::span<const std::string> overrides,
                 AssetLibrary* assets) {
  std::unique_ptr<AssetLibrary> ownAssets;
  if (!assets) {
    ownAssets = std::make_unique<AssetLibrary>(buildAssetScene);
    assets = ownAssets.get();
  }
  Diagnostics diag;
  Scene scene;
  scene.sourcePath = doc.path;
  scene.sourceDir = doc.path.empty() ? "." : std::filesystem::path(doc.path).parent_path().string();
  if (scene.sourceDir.empty()) scene.sourceDir = ".";
  const RawNode& root = doc.root;
  SourceLoc fileLoc{doc.path, 1, 1};

  if (root.isNull()) {
    diag.error(fileLoc, "the scene file is empty; a scene is a mapping with at least `version: 1` and `prims:`");
    diag.throwIfErrors();
  }
  MapReader top(root, "", diag);
  if (!top.ok()) diag.throwIfErrors();

  if (const RawNode* version = top.require("version")) {
    AttributeSpec spec;
    spec.type = ValueType::Int;
    if (auto v = readValue(*version, spec, "version", diag); v && v->get<int32_t>() != kSceneFormatVersion)
      diag.error(version->loc, "version: this sdgbehave reads scene format version " +
                                   std::to_string(kSceneFormatVersion) + ", found " + version->scalar);
  }
  if (const RawNode* n = top.get("stage")) readStageSection(*n, scene.stage, diag);
  if (const RawNode* n = top.get("asset_roots")) scene.assetRoots = readStringList(*n, "asset_roots", diag);
  if (const RawNode* n = top.get("plugins")) scene.plugins = readStringList(*n, "plugins", diag);
  if (const RawNode* n = top.get("scripts")) scene.scripts = readStringList(*n, "scripts", diag);
  if (const RawNode* n = top.get("isaac_assets")) {
    if (auto s = readString(*n, "isaac_assets", diag)) {
      scene.isaacAssets = *s;
      scene.isaacAssetsLoc = n->loc;
    }
  }
  readSettingSections(top, scene, diag);
  // A nested asset's build has no overrides: it keeps the top scene's selections.
  if (!overrides.empty()) assets->setVariantSelections(variantSelections(overrides, diag));
  if (const RawNode* prims = top.require("prims"))
    readPrims(*prims, catalog, scene.stage, diag, PrimReferences{assets, scene.sourceDir});
  if (!diag.hasErrors() && !overrides.empty())
    for (const VariantSelection& v : assets->unusedVariantSelections())
      diag.error(v.loc, v.prim + " is not a prim of a USD file the scene mounts (reference: "
                                         "FILE.usd); variant selections apply to USD prims");
  top.finish();

  // Overrides apply to a scene that parsed; their own problems join the list.
  if (!diag.hasErrors()) applyOverrides(overrides, catalog, scene, diag);
  applyRenderSettingsToStage(scene);
  if (!diag.hasErrors()) validateScene(scene, catalog, diag);
  diag.throwIfErrors();
  return scene;
}

Scene loadScene(const std::string& path, const BehaviorCatalog& catalog, std::span<const std::string> overrides) {
  return buildScene(readSceneDocument(path), catalog, overrides);
}

Scene buildAssetScene(const SceneDocument& doc, const BehaviorCatalog& catalog, AssetLibrary& assets) {
  return buildScene(doc, catalog, {}, &assets);
}

}  // namespace sdg
