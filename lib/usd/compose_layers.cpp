// Composition: layers read once each, layer stacks (a layer and its
// sublayers, strongest first, with their time offsets), asset paths
// resolved against the layer that wrote them, and map functions.
#include <filesystem>

#include "usd/compose_internal.h"
#include "usd/layer_io.h"
#include "usd/sdf_path.h"

namespace sdg::usd {

namespace {

bool isPackage(const std::string& identifier) {
  return identifier.size() > 5 && identifier.compare(identifier.size() - 5, 5, ".usdz") == 0;
}

std::string normal(const std::filesystem::path& p) { return p.lexically_normal().generic_string(); }

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

std::string resolveAssetPath(const std::string& assetPath, const std::string& anchorIdentifier) {
  if (auto [package, entry] = splitPackagePath(assetPath); !entry.empty())  // "pkg.usdz[inner]" as written
    return resolveAssetPath(package, anchorIdentifier) + "[" + normal(entry) + "]";
  if (!assetPath.empty() && assetPath[0] == '/') return normal(assetPath);
  auto [package, entry] = splitPackagePath(anchorIdentifier);
  if (!entry.empty() || isPackage(anchorIdentifier)) {
    // Inside a package: relative to the writing entry's folder, in the package.
    std::string inner = normal(std::filesystem::path(entry).parent_path() / assetPath);
    if (inner.rfind("../", 0) != 0 && inner != "..") return package + "[" + inner + "]";
    // Climbing out of the package root leads to the package's folder.
    return normal(std::filesystem::path(package).parent_path() / inner.substr(inner == ".." ? 2 : 3));
  }
  return normal(std::filesystem::path(anchorIdentifier).parent_path() / assetPath);
}

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
    throw usdErrorAt(from, arcText + " (" + identifier + "): " + e.what());
  } catch (const std::exception& e) {
    throw usdErrorAt(from, arcText + " (" + identifier + "): " + e.what());
  }
  if (!layer->spec("/")) {  // a reader that gives no pseudo-root still yields a usable, empty layer
    layer->specs["/"].type = SpecType::PseudoRoot;
  }
  if (layer->identifier.empty()) layer->identifier = identifier;
  // Asset paths in the layer resolve against the identifier it was opened by.
  layer->identifier = identifier;
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
    SourceLoc at(layer.identifier, root.loc.line, root.loc.column);
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
