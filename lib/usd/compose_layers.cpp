// Composition: layers read once each, layer stacks (a layer and its
// sublayers, strongest first, with their time offsets), asset paths
// resolved against the layer that wrote them (asset_paths.cpp), and map
// functions.
#include "usd/asset_paths.h"
#include "usd/compose_internal.h"
#include "usd/layer_io.h"
#include "usd/sdf_path.h"

namespace sdg::usd {

namespace {

LayerUnits unitsOf(const Layer& layer) {
  LayerUnits units;
  units.layer = layer.identifier;
  const Spec& root = layer.pseudoRoot();
  if (const Value* v = root.field(field::kMetersPerUnit); v && isNumeric(v->kind) && !v->isArray)
    units.metersPerUnit = v->numbers.at(0);
  if (const Value* v = root.field(field::kUpAxis); v && isText(v->kind) && !v->isArray) units.upAxis = v->asString();
  return units;
}

}  // namespace

LayerReader textLayerFileReader(const ReadLimits& limits) {
  return [limits](const std::string& identifier) { return readTextLayerFile(identifier, limits); };
}

namespace detail {

std::optional<std::string> MapFunction::map(const std::string& p) const {
  std::string stripped = path::stripVariants(p);
  const std::pair<std::string, std::string>* best = nullptr;
  for (const auto& pair : pairs)
    if (path::hasPrefix(stripped, pair.first) && (!best || pair.first.size() > best->first.size())) best = &pair;
  if (!best) return std::nullopt;
  return path::replacePrefix(stripped, best->first, best->second);
}

const Layer& LayerCache::layer(const std::string& identifier, const SourceLoc& from, const std::string& arcText) {
  auto it = layers_.find(identifier);
  if (it != layers_.end()) return *it->second;
  if (layers_.size() >= limits_.maxLayers)
    throw usdErrorAt(from, arcText + ": more than " + std::to_string(limits_.maxLayers) + " layers, the limit");
  std::unique_ptr<Layer> layer;
  try {
    layer = std::make_unique<Layer>(reader_(identifier));
  } catch (const UsdError& e) {
    // The root layer's own syntax errors are reported at their file:line:col
    // first, as a YAML scene's are; an arc's name the arc that read them.
    if (!from.known() && e.loc().line > 0) throw;
    // The layer is named once: in the arc's words, or by the message itself
    // when that starts with it ("x.usd is a Git LFS pointer, ...").
    std::string why = e.what();
    if (e.loc().line == 0 && why.starts_with(identifier + ": ")) why.erase(0, identifier.size() + 2);
    if (why.starts_with(identifier + " ")) throw usdErrorAt(from, arcText + ": " + why);
    throw usdErrorAt(from, arcText + " (" + identifier + "): " + why);
  } catch (const std::exception& e) {
    throw usdErrorAt(from, arcText + " (" + identifier + "): " + e.what());
  }
  if (!layer->spec("/")) {  // a reader that gives no pseudo-root still yields a usable, empty layer
    layer->specs["/"].type = SpecType::PseudoRoot;
  }
  // Asset paths in the layer resolve against the identifier it was opened
  // by, except a package opened by its name: its root layer is an entry,
  // "pkg.usdz[dir/root.usdc]", whose folder in the package anchors them.
  const bool packageRoot = namesPackage(identifier) && splitPackagePathInner(layer->identifier).first == identifier;
  if (!packageRoot) layer->identifier = identifier;
  opened_.push_back(identifier);
  return *layers_.emplace(identifier, std::move(layer)).first->second;
}

const LayerStack& LayerCache::stack(const std::string& identifier, const SourceLoc& from, const std::string& arcText) {
  auto it = stacks_.find(identifier);
  if (it != stacks_.end()) return *it->second;
  auto stack = std::make_unique<LayerStack>();
  stack->identifier = identifier;
  const Layer& root = layer(identifier, from, arcText);
  stack->layers.push_back(&root);
  stack->offsets.push_back(LayerOffset{});
  stack->units = unitsOf(root);
  std::vector<std::string> chain{identifier};
  addSublayers(*stack, root, LayerOffset{}, chain);
  return *stacks_.emplace(identifier, std::move(stack)).first->second;
}

void LayerCache::addSublayers(LayerStack& stack, const Layer& layer, const LayerOffset& offset,
                              std::vector<std::string>& chain) {
  const Spec& root = layer.pseudoRoot();
  const Value* subLayers = root.field(field::kSubLayers);
  if (!subLayers) return;
  const Value* offsets = root.field(field::kSubLayerOffsets);
  for (size_t i = 0; i < subLayers->strings.size(); ++i) {
    const std::string& written = subLayers->strings[i];
    std::string resolved = resolveAssetPath(written, layer.identifier);
    SourceLoc at = i < layer.subLayerLocs.size() ? layer.subLayerLocs[i]
                                                 : SourceLoc(layer.identifier, root.loc.line, root.loc.column);
    std::string arcText = "sublayer @" + written + "@";
    for (const std::string& open : chain)
      if (open == resolved) {
        std::string cycle;
        for (const std::string& c : chain) cycle += c + " -> ";
        throw usdErrorAt(at, "sublayer cycle: " + cycle + resolved);
      }
    if (chain.size() >= limits_.maxArcDepth)
      throw usdErrorAt(at, arcText + ": sublayers nested deeper than " + std::to_string(limits_.maxArcDepth));
    LayerOffset own = offsets && offsets->layerOffsets && i < offsets->layerOffsets->size()
                          ? (*offsets->layerOffsets)[i]
                          : LayerOffset{};
    LayerOffset total = concat(offset, own);
    const Layer& sub = this->layer(resolved, at, arcText);
    stack.layers.push_back(&sub);
    stack.offsets.push_back(total);
    chain.push_back(resolved);
    addSublayers(stack, sub, total, chain);
    chain.pop_back();
  }
}

}  // namespace detail
}  // namespace sdg::usd
