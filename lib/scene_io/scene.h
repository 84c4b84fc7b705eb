#pragma once
// A loaded scene: the stage plus the run-level settings that sit beside the
// prims in the YAML file (render, writers, capture, physics, run, events,
// asset roots, plugins). Plain data; the code that applies it lives in run/.
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/payload.h"
#include "core/source_loc.h"
#include "stage/stage.h"
#include "stage/value.h"

namespace sdg {

// Options of one settings section, every option present (defaults filled in).
class OptionSet {
 public:
  OptionSet() = default;
  explicit OptionSet(std::span<const AttributeSpec> specs);

  const Value& get(std::string_view name) const;
  bool getBool(std::string_view name) const { return get(name).get<bool>(); }
  uint32_t getUInt(std::string_view name) const { return get(name).get<uint32_t>(); }
  int32_t getInt(std::string_view name) const { return get(name).get<int32_t>(); }
  const std::string& getString(std::string_view name) const { return get(name).get<std::string>(); }
  void set(const std::string& name, Value value, const SourceLoc& loc = {});
  bool isAuthored(std::string_view name) const { return locs_.count(name) != 0; }
  const SourceLoc* locOf(std::string_view name) const;
  const std::map<std::string, Value, std::less<>>& values() const { return values_; }
  bool operator==(const OptionSet& o) const { return values_ == o.values_; }

 private:
  std::map<std::string, Value, std::less<>> values_;
  std::map<std::string, SourceLoc, std::less<>> locs_;
};

struct WriterConfig {
  std::string type;  // a name of writerTypes(): "BasicWriter", "CocoWriter", "BopWriter"
  OptionSet options;
  SourceLoc loc;
  bool operator==(const WriterConfig& o) const { return type == o.type && options == o.options; }
};

// One step of the pre-roll: publish an event, then wait for a reply whose
// payload contains `waitFor`, for at most `maxUpdates` updates.
struct EventStep {
  std::string publish;
  Payload payload;
  std::string waitEvent;  // defaults to `publish` with ".in" replaced by ".out"
  Payload waitFor;
  uint32_t maxUpdates = 100;
  SourceLoc loc;
  bool operator==(const EventStep& o) const {
    return publish == o.publish && payload == o.payload && waitEvent == o.waitEvent && waitFor == o.waitFor &&
           maxUpdates == o.maxUpdates;
  }
};

struct Scene {
  std::string sourcePath;  // the YAML file ("" when built in memory)
  std::string sourceDir;   // its folder, the first asset root
  Stage stage;
  OptionSet render;
  OptionSet capture;
  OptionSet physics;
  OptionSet run;  // how the run guards itself (run.hook_timeout)
  std::vector<WriterConfig> writers;
  std::vector<EventStep> events;
  std::vector<std::string> assetRoots;
  std::vector<std::string> plugins;
  std::vector<std::string> scripts;  // behavior scripts (.py), relative to the scene file
  // A local copy of Isaac Sim's asset pack, relative to the scene file
  // ("" = none); --isaac-assets and SDGBEHAVE_ISAAC_ASSETS take precedence.
  std::string isaacAssets;
  SourceLoc isaacAssetsLoc;

  Scene();
  bool operator==(const Scene& o) const {
    return stage == o.stage && render == o.render && capture == o.capture && physics == o.physics && run == o.run &&
           writers == o.writers &&
           events == o.events && assetRoots == o.assetRoots && plugins == o.plugins && scripts == o.scripts && isaacAssets == o.isaacAssets;
  }
};

// Copies the render settings the stage's geometry depends on
// (render.subdivision_level) into its metadata; the loaders call it once
// the settings are final (after --set).
void applyRenderSettingsToStage(Scene& scene);

// The option tables, shared by the loader, the writer and the JSON Schema.
std::span<const AttributeSpec> stageOptionSpecs();
std::span<const AttributeSpec> renderOptionSpecs();
std::span<const AttributeSpec> physicsOptionSpecs();
std::span<const AttributeSpec> captureOptionSpecs();
std::span<const AttributeSpec> runOptionSpecs();
struct WriterTypeInfo {
  std::string_view name;
  std::string_view doc;
  std::span<const AttributeSpec> options;
};
std::span<const WriterTypeInfo> writerTypes();
const WriterTypeInfo* findWriterType(std::string_view name);

inline constexpr int kSceneFormatVersion = 1;
inline constexpr int kMaxResolution = 16384;  // per side; documented limit

}  // namespace sdg
