#pragma once
// Composition: a root layer and everything it brings in (sublayers,
// references, payloads, variants, inherits, specializes) composed into one
// tree of prims, in USD's strength order (LIVRPS: local, inherits,
// variants, references, payloads, specializes; within each, the order the
// arcs are listed; sublayers stronger than the layers after them).
//
// Each composed prim and property keeps where its strongest opinion was
// written and which layers contributed, so errors found later can point at
// a file:line:col. Values are resolved at one time code (the stage's start
// time code unless given): the default, or the time samples at that time,
// linearly interpolated where USD interpolates.
//
// Layers are read through a callback given a resolved identifier (a file
// path or a package entry "pkg.usdz[inner.usdc]"), so tests can compose
// in-memory layers and packages resolve their asset paths inside
// themselves.
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "usd/layer.h"

namespace sdg::usd {

// Reads the layer with this resolved identifier (throws UsdError).
using LayerReader = std::function<Layer(const std::string& identifier)>;

// Variant selections that override the authored ones: prim path (in the
// composed namespace) -> variant set -> variant.
using VariantOverrides = std::map<std::string, std::map<std::string, std::string>>;

struct ComposeLimits {
  size_t maxPrims = size_t(1) << 22;         // composed prims in all
  size_t maxArcsPerPrim = 4096;              // nodes of one prim's index
  size_t maxLayers = 4096;                   // distinct layers opened
  uint32_t maxArcDepth = 64;                 // arcs nested in arcs (a reference in a reference ...)
  uint32_t maxNamespaceDepth = 512;          // prim path depth
};

struct ComposeOptions {
  VariantOverrides variantOverrides;
  std::optional<double> timeCode;  // default: the root layer's startTimeCode (0 when not authored)
  ComposeLimits limits;
};

// The arcs of USD, in strength order.
enum class ArcType : uint8_t { Root, Inherit, Variant, Reference, Payload, Specialize };
const char* arcTypeName(ArcType arc);

// A layer's units (USD's fallbacks: 0.01 metres per unit, Y up).
struct LayerUnits {
  double metersPerUnit = 0.01;
  std::string upAxis = "Y";
  std::string layer;  // the layer that says so (its identifier)
  bool operator==(const LayerUnits& o) const { return metersPerUnit == o.metersPerUnit && upAxis == o.upAxis; }
};

// An attribute's time samples as the layer that wins wrote them, with the
// layer offset that carries them onto the stage's time codes (sublayer and
// reference offsets): valueAt(t) is what composing at time code t gives.
// Kept so that a stage's own animation can be played without composing
// again (scene_io/usd_animation.h).
struct AttributeSamples {
  std::shared_ptr<const TimeSamples> samples;  // in the layer's time
  LayerOffset toStage;                         // stage time = offset + scale * layer time
  // The samples' times on the stage's time line, ascending.
  std::vector<double> stageTimes() const;
  // Held before the first and after the last sample, interpolated between
  // two where USD interpolates; Empty where a block (`None`) applies.
  Value valueAt(double stageTime) const;
  // More than one sample and not all alike: the value changes over time.
  bool varies() const;
};

struct ComposedProperty {
  std::string name;
  bool isRelationship = false;
  std::string typeName;  // attributes: "point3f[]", "color3f", "asset", ...
  Variability variability = Variability::Varying;
  bool custom = false;
  // The resolved value: Empty when nothing is authored or the strongest
  // opinion is a block (`None`).
  Value value;
  bool fromTimeSamples = false;  // `value` comes from time samples
  // The samples `value` was taken from (null when it is a default or none).
  std::shared_ptr<const AttributeSamples> samples;
  std::string valueLayer;        // the layer that holds `value` ("" when none)
  // Asset values (asset, asset[]): each path resolved against valueLayer
  // (a file path, or "pkg.usdz[inner]" inside a package).
  std::vector<std::string> resolvedAssets;
  std::vector<std::string> connections;  // attributes, in the composed namespace
  std::vector<std::string> targets;      // relationships, in the composed namespace
  std::map<std::string, Value> metadata;  // interpolation, elementSize, colorSpace, customData, ...
  SourceLoc loc;                          // the strongest opinion
  std::vector<std::string> layers;        // layers with opinions, strongest first
};

struct ComposedVariantSet {
  std::string name;
  std::vector<std::string> variants;  // every variant the set offers
  std::string selection;              // "" when none applies
};

struct ComposedPrim {
  std::string path;
  std::string typeName;
  Specifier specifier = Specifier::Over;
  bool defined = false;   // `def` (or `class`) here and on every ancestor: on the stage
  bool abstract = false;  // a class, or under one
  std::string kind;
  bool active = true;
  bool instanceable = false;
  std::vector<std::string> apiSchemas;
  // Every other composed field (customData, assetInfo, displayName, documentation, hidden, ...).
  std::map<std::string, Value> metadata;
  std::vector<ComposedVariantSet> variantSets;
  std::vector<ComposedProperty> properties;  // in USD's order
  std::vector<std::string> children;         // names, in USD's order (none when inactive)
  SourceLoc loc;                             // the strongest opinion
  std::vector<std::string> layers;           // layers with opinions, strongest first
  // Set on a prim that references or payloads a layer whose units
  // (metersPerUnit, upAxis) differ from those of the layer that wrote the
  // arc: the mapping onto the stage inserts the correcting transform here.
  struct UnitsChange {
    LayerUnits asset;  // the referenced layer's units
    LayerUnits into;   // the referencing layer's (the stage's at the top level)
  };
  std::optional<UnitsChange> unitsChange;

  const ComposedProperty* property(const std::string& name) const;
};

// Something USD would report and go on from. `feature` names what was left
// out, for a summary of losses ("relocates", "non-USD reference", ...).
struct ComposeWarning {
  SourceLoc loc;        // where it was written (unknown for some)
  std::string feature;
  std::string message;  // whole, starting with the location where there is one
};

struct ComposedStage {
  std::string rootLayer;
  LayerUnits units;  // the root layer's
  std::string defaultPrim;
  double timeCode = 0;  // the time values were resolved at
  std::map<std::string, Value> layerMetadata;  // the root layer's metadata
  std::vector<ComposedPrim> prims;             // depth first, parents before children
  std::vector<std::string> layers;             // every layer opened, in the order opened
  // Things USD would report and go on from: targets outside a reference's
  // scope, variant selections naming no variant, relocates (not supported).
  std::vector<ComposeWarning> warnings;

  const ComposedPrim* prim(const std::string& path) const;
  std::vector<std::string> rootPrims() const;  // paths of the prims under "/"

 private:
  friend class Composer;
  std::map<std::string, size_t> index_;
};

// Composes the stage whose root layer is `rootIdentifier` (read through `reader`).
ComposedStage composeStage(const std::string& rootIdentifier, const LayerReader& reader,
                           const ComposeOptions& options = {});

// Resolves an asset path written in the layer `anchorIdentifier`: relative
// paths against the layer's folder (inside the package for a package entry
// or a .usdz), absolute ones as they are; "." and ".." are folded.
std::string resolveAssetPath(const std::string& assetPath, const std::string& anchorIdentifier);

// A reader of layer files on disk for text layers (readTextLayerFile).
LayerReader textLayerFileReader(const ReadLimits& limits = {});

}  // namespace sdg::usd
