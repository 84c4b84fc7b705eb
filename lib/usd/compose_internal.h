#pragma once
// Composition's internals, shared by its source files:
//   compose_layers.cpp  layers read once, layer stacks (sublayers with offsets), asset path resolution
//   compose_index.cpp   the prim index: the graph of sites (layer stack + path) that hold a prim's opinions
//   compose_values.cpp  resolving fields, values (time samples), list ops and paths over an index
//   compose.cpp         the traversal that builds ComposedStage
// The model follows Pcp's: a prim index is a tree of nodes, each a site
// reached through an arc, with a map function from the node's namespace
// into the root's; strength order is a depth-first walk of that tree with
// each node's children sorted by arc type, then by the namespace depth the
// arc was introduced at (deeper first), then by the order written.
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "usd/compose.h"

namespace sdg::usd::detail {

// Maps paths from one namespace into another by prefix: the longest
// matching source prefix is replaced by its target. Variant selections are
// stripped before mapping (paths inside a variant are written without them).
struct MapFunction {
  std::vector<std::pair<std::string, std::string>> pairs;  // source prefix -> target prefix

  static MapFunction identity() { return MapFunction{{{"/", "/"}}}; }
  std::optional<std::string> map(const std::string& path) const;
};

// t_outer = offset + scale * t_inner.
inline LayerOffset concat(const LayerOffset& outer, const LayerOffset& inner) {
  return LayerOffset{outer.offset + outer.scale * inner.offset, outer.scale * inner.scale};
}

struct LayerStack {
  std::string identifier;                 // the root layer's
  std::vector<const Layer*> layers;       // strongest first
  std::vector<LayerOffset> offsets;       // each layer's time offset into the stack's root
  LayerUnits units;                       // the root layer's
};

// Opens each layer once and builds each layer stack once.
class LayerCache {
 public:
  LayerCache(const LayerReader& reader, const ComposeLimits& limits) : reader_(reader), limits_(limits) {}

  // The layer stack rooted at `identifier`; `from` says where it was asked
  // for (errors: "referenced from a.usda:3:5").
  const LayerStack& stack(const std::string& identifier, const SourceLoc& from, const std::string& arcText);
  const std::vector<std::string>& openedOrder() const { return opened_; }

 private:
  const Layer& layer(const std::string& identifier, const SourceLoc& from, const std::string& arcText);
  void addSublayers(LayerStack& stack, const Layer& layer, const LayerOffset& offset,
                    std::vector<std::string>& chain);

  const LayerReader& reader_;
  ComposeLimits limits_;
  std::unordered_map<std::string, std::unique_ptr<Layer>> layers_;
  std::unordered_map<std::string, std::unique_ptr<LayerStack>> stacks_;
  std::vector<std::string> opened_;
};

struct Node {
  const LayerStack* stack = nullptr;
  std::string path;     // the site's path in the stack (may hold variant selections)
  ArcType arc = ArcType::Root;
  int parent = -1;
  std::vector<int> children;  // strongest first
  // From this node's namespace to the root's, applied in order (this node's
  // own map first). Empty for the root.
  std::vector<const MapFunction*> mapsToRoot;
  LayerOffset offsetToRoot;
  int namespaceDepth = 0;  // depth of the root path at which the arc was added
  int siblingNumber = 0;   // position in the authored list
  SourceLoc arcLoc;        // where the arc was written
  bool arcsDone = false;      // direct arcs at this site evaluated
  int variantSetsDone = 0;    // variant sets at this site evaluated so far (one at a time, strongest node first)
  bool variantsDone = false;  // all of them
  bool hasSpecs = false;      // some layer of the stack has a spec at `path`
  bool internal = false;      // a reference or payload into its own layer stack
};

// One prim's index: the nodes, the root first; `order` lists them strongest first.
struct PrimIndex {
  std::vector<Node> nodes;
  std::vector<int> order;
  std::vector<std::shared_ptr<const MapFunction>> maps;  // owned map functions
  // Variant sets evaluated at this prim: (set, selection), for the composed prim's record.
  std::vector<std::pair<std::string, std::string>> selections;

  void computeOrder();
  std::optional<std::string> mapToRoot(const Node& node, const std::string& path) const;
};

// Builds prim indexes and reports what it found along the way.
class IndexBuilder {
 public:
  IndexBuilder(LayerCache& cache, const LayerStack& rootStack, const ComposeOptions& options,
               std::vector<ComposeWarning>& warnings)
      : cache_(cache), rootStack_(rootStack), options_(options), warnings_(warnings) {}

  // The index of the prim at `path` (root namespace), from its parent's
  // index (null for a prim under "/").
  PrimIndex build(const std::string& path, const PrimIndex* parentIndex);
  // Variant overrides used so far (set "path\nset").
  const std::vector<std::string>& usedOverrides() const { return usedOverrides_; }

 private:
  void expandArcs(PrimIndex& index, int node, const std::string& primPath);
  bool expandVariants(PrimIndex& index, const std::string& primPath);
  void addImpliedInherits(PrimIndex& index, int node, const std::string& classPath, int sibling, const SourceLoc& at);
  // Adds `node` under `parent`, its map function `map` leading into the
  // namespace of `chainFrom` (the parent unless given: propagated
  // specializes sit under the root but map through their origin).
  int addNode(PrimIndex& index, int parent, Node node, std::shared_ptr<const MapFunction> map, int chainFrom = -1);
  void addReferenceArcs(PrimIndex& index, int node, const std::string& primPath, bool payload);
  void addClassArcs(PrimIndex& index, int node, const std::string& primPath, bool specializes);
  void checkCycle(const PrimIndex& index, int parent, const LayerStack* stack, const std::string& path,
                  const SourceLoc& at, const std::string& arcText) const;
  std::string findSelection(const PrimIndex& index, const std::string& set) const;

  LayerCache& cache_;
  const LayerStack& rootStack_;
  const ComposeOptions& options_;
  std::vector<ComposeWarning>& warnings_;
  std::vector<std::string> usedOverrides_;
};

// ---- field access over sites (compose_values.cpp)

// Calls `fn(spec, layerIndex)` for every spec at `path` in `stack`, strongest layer first.
template <class Fn>
void forEachSpec(const LayerStack& stack, const std::string& path, Fn&& fn) {
  for (size_t i = 0; i < stack.layers.size(); ++i)
    if (const Spec* spec = stack.layers[i]->spec(path)) fn(*spec, i);
}

// A list op's items composed over a layer stack (weakest layer first, each
// op applied to the result so far), each with the layer that wrote it.
template <class T>
struct SourcedItem {
  T item;
  size_t layerIndex;
  bool operator==(const SourcedItem& o) const { return item == o.item; }
};
template <class T>
auto listOpKey(const SourcedItem<T>& sourced) {
  return sdg::usd::listOpKey(sourced.item);
}
std::vector<SourcedItem<std::string>> composeTextListOp(const LayerStack& stack, const std::string& path,
                                                        const char* field);
std::vector<SourcedItem<Reference>> composeReferenceListOp(const LayerStack& stack, const std::string& path,
                                                           const char* field);

// Resolves an attribute's value over an index's property sites at a time code.
struct ResolvedValue {
  Value value;
  bool fromTimeSamples = false;
  const Layer* layer = nullptr;  // the layer that holds it
  std::shared_ptr<const AttributeSamples> samples;  // when it comes from time samples
};
// Time samples at `time` (the layer's time): held outside them, linearly
// interpolated between two where USD interpolates.
Value sampleAt(const TimeSamples& samples, double time);
ResolvedValue resolveAttributeValue(const PrimIndex& index, const std::string& propertyName, double time);

// Linear interpolation between two samples where USD interpolates (floating
// point scalars, vectors, matrices; quaternions by slerp; arrays of equal
// length); otherwise nullopt (the earlier sample is held).
std::optional<Value> interpolate(const Value& a, const Value& b, double t);

}  // namespace sdg::usd::detail
