// Composition: the traversal. Each prim's index is built from its parent's,
// then the prim's fields, properties and children are resolved over the
// index's sites in strength order.
#include "usd/compose.h"

#include <algorithm>
#include <set>
#include <unordered_set>

#include "usd/compose_internal.h"
#include "usd/sdf_path.h"

namespace sdg::usd {

using detail::IndexBuilder;
using detail::LayerCache;
using detail::LayerStack;
using detail::Node;
using detail::PrimIndex;

const ComposedProperty* ComposedPrim::property(const std::string& name) const {
  for (const ComposedProperty& p : properties)
    if (p.name == name) return &p;
  return nullptr;
}

const ComposedPrim* ComposedStage::prim(const std::string& path) const {
  auto it = index_.find(path);
  return it == index_.end() ? nullptr : &prims[it->second];
}

std::vector<std::string> ComposedStage::rootPrims() const {
  std::vector<std::string> out;
  for (const ComposedPrim& p : prims)
    if (path::parent(p.path) == "/") out.push_back(p.path);
  return out;
}

namespace {

// One opinion: a spec at a site of the index, in strength order.
struct Opinion {
  const Spec* spec;
  const Layer* layer;
  int node;
};

// Fields resolved by composition itself rather than kept as metadata.
bool isStructuralPrimField(const std::string& name) {
  static const std::set<std::string> kFields = {
      field::kSpecifier,      field::kTypeName,       field::kPrimChildren,     field::kProperties,
      field::kPrimOrder,      field::kPropertyOrder,  field::kVariantSetNames,  field::kVariantSetChildren,
      field::kVariantSelection, field::kReferences,   field::kPayload,          field::kInheritPaths,
      field::kSpecializes,    field::kKind,           field::kActive,           field::kInstanceable,
      field::kApiSchemas,     field::kRelocates,      field::kVariantChildren};
  return kFields.count(name) > 0;
}

bool isStructuralPropertyField(const std::string& name) {
  static const std::set<std::string> kFields = {field::kTypeName,        field::kVariability, field::kCustom,
                                                field::kDefault,         field::kTimeSamples, field::kConnectionPaths,
                                                field::kTargetPaths,     "targetChildren",    "connectionChildren"};
  return kFields.count(name) > 0;
}

// Stronger keys win; dictionaries under the same key merge recursively.
void mergeWeakerDictionary(Dictionary& into, const Dictionary& weaker) {
  for (const auto& [key, value] : weaker) {
    auto it = into.find(key);
    if (it == into.end()) {
      into.emplace(key, value);
    } else if (it->second.kind == Kind::Dictionary && value.kind == Kind::Dictionary && it->second.dictionary &&
               value.dictionary) {
      Dictionary merged = *it->second.dictionary;
      mergeWeakerDictionary(merged, *value.dictionary);
      it->second.dictionary = std::make_shared<Dictionary>(std::move(merged));
    }
  }
}

// Metadata of a prim or property: the strongest opinion of each field,
// dictionaries merged over all opinions, list ops applied weakest first.
std::map<std::string, Value> composeMetadata(const std::vector<Opinion>& opinions, bool (*structural)(const std::string&)) {
  std::map<std::string, Value> out;
  for (auto it = opinions.rbegin(); it != opinions.rend(); ++it) {  // weakest first
    for (const auto& [name, value] : it->spec->fields) {
      if (structural(name)) continue;
      auto existing = out.find(name);
      if (existing == out.end() || value.kind == Kind::ValueBlock) {
        out[name] = value;
      } else if (value.kind == Kind::Dictionary && existing->second.kind == Kind::Dictionary && value.dictionary &&
                 existing->second.dictionary) {
        Dictionary merged = *value.dictionary;
        mergeWeakerDictionary(merged, *existing->second.dictionary);
        existing->second = Value::dict(std::move(merged));
      } else if (value.textListOp && existing->second.textListOp) {
        Value applied = value;
        auto composed = std::make_shared<ListOp<std::string>>();
        composed->isExplicit = true;
        composed->explicitItems = value.textListOp->applyTo(existing->second.textListOp->applyTo({}));
        applied.textListOp = composed;
        existing->second = applied;
      } else {
        existing->second = value;
      }
    }
  }
  return out;
}

template <class T>
const Value* strongestField(const std::vector<Opinion>& opinions, const char* name, T accept) {
  for (const Opinion& o : opinions)
    if (const Value* v = o.spec->field(name); v && accept(*v)) return v;
  return nullptr;
}

bool scalarText(const Value& v) { return isText(v.kind) && !v.isArray && !v.strings.empty(); }
bool scalarBool(const Value& v) { return v.kind == Kind::Bool && !v.isArray && v.numbers.size() == 1; }

std::vector<std::string> contributingLayers(const std::vector<Opinion>& opinions) {
  std::vector<std::string> out;
  for (const Opinion& o : opinions)
    if (std::find(out.begin(), out.end(), o.layer->identifier) == out.end()) out.push_back(o.layer->identifier);
  return out;
}

// Names from every opinion, weakest first, each opinion's reorder statement applied as it comes.
std::vector<std::string> composeNames(const std::vector<Opinion>& opinions, const char* namesField,
                                      const char* orderField) {
  std::vector<std::string> names;
  std::unordered_set<std::string> seen;
  for (auto it = opinions.rbegin(); it != opinions.rend(); ++it) {
    if (const Value* v = it->spec->field(namesField))
      for (const std::string& name : v->strings)
        if (seen.insert(name).second) names.push_back(name);
    if (const Value* order = it->spec->field(orderField)) {
      ListOp<std::string> op;
      op.orderedItems = order->strings;
      names = op.applyTo(names);
    }
  }
  return names;
}

}  // namespace

class Composer {
 public:
  Composer(const std::string& rootIdentifier, const LayerReader& reader, const ComposeOptions& options)
      : options_(options), cache_(reader, options.limits) {
    rootStack_ = &cache_.stack(rootIdentifier, SourceLoc(), "the root layer");
    builder_ = std::make_unique<IndexBuilder>(cache_, *rootStack_, options_, stage_.warnings);
  }

  ComposedStage run() {
    const Layer& root = *rootStack_->layers.front();
    stage_.rootLayer = root.identifier;
    stage_.units = rootStack_->units;
    for (const auto& [name, value] : root.pseudoRoot().fields)
      if (name != field::kPrimChildren && name != field::kPrimOrder) stage_.layerMetadata[name] = value;
    if (const Value* v = root.pseudoRoot().field(field::kDefaultPrim); v && scalarText(*v)) stage_.defaultPrim = v->asString();
    stage_.timeCode = 0;
    if (options_.timeCode) {
      stage_.timeCode = *options_.timeCode;
    } else if (const Value* v = root.pseudoRoot().field(field::kStartTimeCode); v && isNumeric(v->kind) && !v->isArray) {
      stage_.timeCode = v->numbers.at(0);
    }
    std::vector<Opinion> rootOpinions;
    for (const Layer* layer : rootStack_->layers) rootOpinions.push_back({&layer->pseudoRoot(), layer, 0});
    for (const std::string& name : composeNames(rootOpinions, field::kPrimChildren, field::kPrimOrder))
      composePrim(path::child("/", name), nullptr, true, false);
    checkOverridesUsed();
    stage_.layers = cache_.openedOrder();
    return std::move(stage_);
  }

 private:
  void composePrim(const std::string& primPath, const PrimIndex* parentIndex, bool parentDefined, bool parentAbstract);
  void composeProperties(ComposedPrim& prim, const PrimIndex& index, const std::vector<Opinion>& opinions);
  std::vector<std::string> composePaths(const PrimIndex& index, const std::string& propertyName, const char* fieldName,
                                        const std::string& composedPath);
  void checkOverridesUsed() const;

  ComposeOptions options_;
  LayerCache cache_;
  const LayerStack* rootStack_ = nullptr;
  std::unique_ptr<IndexBuilder> builder_;
  ComposedStage stage_;
};

void Composer::composePrim(const std::string& primPath, const PrimIndex* parentIndex, bool parentDefined,
                           bool parentAbstract) {
  if (static_cast<uint32_t>(path::depth(primPath)) > options_.limits.maxNamespaceDepth)
    throw usdErrorAt(SourceLoc(), primPath.substr(0, 200) + "...: prims nested deeper than " +
                                      std::to_string(options_.limits.maxNamespaceDepth) + ", the limit");
  PrimIndex index = builder_->build(primPath, parentIndex);
  std::vector<Opinion> opinions;
  for (int n : index.order) {
    const Node& node = index.nodes[static_cast<size_t>(n)];
    if (!node.hasSpecs) continue;
    for (const Layer* layer : node.stack->layers)
      if (const Spec* spec = layer->spec(node.path)) opinions.push_back({spec, layer, n});
  }
  if (opinions.empty()) return;  // a child named by a spec that is not there
  if (stage_.prims.size() >= options_.limits.maxPrims)
    throw usdErrorAt(opinions.front().spec->loc, "more than " + std::to_string(options_.limits.maxPrims) +
                                                     " composed prims, the limit");

  ComposedPrim prim;
  prim.path = primPath;
  prim.loc = opinions.front().spec->loc;
  prim.layers = contributingLayers(opinions);
  if (const Value* v = strongestField(opinions, field::kSpecifier, [](const Value& v) {
        return v.kind == Kind::Specifier && v.enumValue != static_cast<int>(Specifier::Over);
      })) {
    prim.specifier = static_cast<Specifier>(v->enumValue);
  }
  prim.abstract = parentAbstract || prim.specifier == Specifier::Class;
  prim.defined = parentDefined && prim.specifier != Specifier::Over;
  if (const Value* v = strongestField(opinions, field::kTypeName, [](const Value& v) {
        return scalarText(v) && !v.asString().empty();
      }))
    prim.typeName = v->asString();
  if (const Value* v = strongestField(opinions, field::kKind, scalarText)) prim.kind = v->asString();
  if (const Value* v = strongestField(opinions, field::kActive, scalarBool)) prim.active = v->asBool();
  if (const Value* v = strongestField(opinions, field::kInstanceable, scalarBool)) prim.instanceable = v->asBool();
  for (auto it = opinions.rbegin(); it != opinions.rend(); ++it)
    if (const Value* v = it->spec->field(field::kApiSchemas); v && v->textListOp)
      prim.apiSchemas = v->textListOp->applyTo(prim.apiSchemas);
  prim.metadata = composeMetadata(opinions, isStructuralPrimField);
  for (const Opinion& o : opinions)
    if (o.spec->field(field::kRelocates))
      stage_.warnings.push_back({o.spec->loc, "relocates", o.spec->loc.str() + ": relocates are not supported; ignored"});

  for (const auto& [set, selection] : index.selections) {
    ComposedVariantSet vs{set, {}, selection};
    for (int n : index.order) {
      const Node& node = index.nodes[static_cast<size_t>(n)];
      detail::forEachSpec(*node.stack, path::variantSet(node.path, set), [&](const Spec& spec, size_t) {
        if (const Value* v = spec.field(field::kVariantChildren))
          for (const std::string& name : v->strings)
            if (std::find(vs.variants.begin(), vs.variants.end(), name) == vs.variants.end()) vs.variants.push_back(name);
      });
    }
    prim.variantSets.push_back(std::move(vs));
  }

  // A reference or payload added at this prim into a layer with other units.
  int depth = path::depth(primPath);
  for (int n : index.order) {
    const Node& node = index.nodes[static_cast<size_t>(n)];
    if ((node.arc != ArcType::Reference && node.arc != ArcType::Payload) || node.internal ||
        node.namespaceDepth != depth)
      continue;
    const LayerUnits& into = index.nodes[static_cast<size_t>(node.parent)].stack->units;
    if (!(node.stack->units == into)) {
      prim.unitsChange = ComposedPrim::UnitsChange{node.stack->units, into};
      break;
    }
  }

  composeProperties(prim, index, opinions);
  if (prim.active) prim.children = composeNames(opinions, field::kPrimChildren, field::kPrimOrder);
  std::vector<std::string> children = prim.children;
  bool defined = prim.defined, abstract = prim.abstract;
  stage_.index_[primPath] = stage_.prims.size();
  stage_.prims.push_back(std::move(prim));
  size_t self = stage_.prims.size() - 1;
  std::vector<std::string> present;
  for (const std::string& name : children) {
    size_t before = stage_.prims.size();
    composePrim(path::child(primPath, name), &index, defined, abstract);
    if (stage_.prims.size() > before) present.push_back(name);
  }
  stage_.prims[self].children = std::move(present);
}

std::vector<std::string> Composer::composePaths(const PrimIndex& index, const std::string& propertyName,
                                                const char* fieldName, const std::string& composedPath) {
  std::vector<std::string> result;
  for (auto it = index.order.rbegin(); it != index.order.rend(); ++it) {  // weakest site first
    const Node& node = index.nodes[static_cast<size_t>(*it)];
    if (!node.hasSpecs) continue;
    std::string propPath = path::property(node.path, propertyName);
    for (size_t i = node.stack->layers.size(); i-- > 0;) {
      const Spec* spec = node.stack->layers[i]->spec(propPath);
      if (!spec) continue;
      const Value* v = spec->field(fieldName);
      if (!v || !v->textListOp) continue;
      // Each path written at this site, mapped into the composed namespace.
      auto mapAll = [&](const std::vector<std::string>& paths, bool report) {
        std::vector<std::string> out;
        for (const std::string& p : paths) {
          if (std::optional<std::string> mapped = index.mapToRoot(node, p)) {
            out.push_back(*mapped);
          } else if (report) {
            stage_.warnings.push_back({spec->loc, "path outside a reference's scope",
                                       composedPath + ": the path <" + p + "> written at " + spec->loc.str() +
                                           " lies outside the scope of the " + arcTypeName(node.arc) +
                                           " that brings it in; ignored"});
          }
        }
        return out;
      };
      const ListOp<std::string>& op = *v->textListOp;
      ListOp<std::string> mapped;
      mapped.isExplicit = op.isExplicit;
      mapped.explicitItems = mapAll(op.explicitItems, true);
      mapped.addedItems = mapAll(op.addedItems, true);
      mapped.prependedItems = mapAll(op.prependedItems, true);
      mapped.appendedItems = mapAll(op.appendedItems, true);
      mapped.deletedItems = mapAll(op.deletedItems, false);
      mapped.orderedItems = mapAll(op.orderedItems, false);
      result = mapped.applyTo(result);
    }
  }
  return result;
}

void Composer::composeProperties(ComposedPrim& prim, const PrimIndex& index, const std::vector<Opinion>& opinions) {
  for (const std::string& name : composeNames(opinions, field::kProperties, field::kPropertyOrder)) {
    std::vector<Opinion> specs;
    for (int n : index.order) {
      const Node& node = index.nodes[static_cast<size_t>(n)];
      if (!node.hasSpecs) continue;
      std::string propPath = path::property(node.path, name);
      for (const Layer* layer : node.stack->layers)
        if (const Spec* spec = layer->spec(propPath)) specs.push_back({spec, layer, n});
    }
    if (specs.empty()) continue;
    ComposedProperty prop;
    prop.name = name;
    prop.isRelationship = specs.front().spec->type == SpecType::Relationship;
    prop.loc = specs.front().spec->loc;
    prop.layers = contributingLayers(specs);
    if (const Value* v = strongestField(specs, field::kTypeName, scalarText)) prop.typeName = v->asString();
    if (const Value* v = strongestField(specs, field::kVariability, [](const Value& v) { return v.kind == Kind::Variability; }))
      prop.variability = static_cast<Variability>(v->enumValue);
    else if (prop.isRelationship)
      prop.variability = Variability::Uniform;
    if (const Value* v = strongestField(specs, field::kCustom, scalarBool)) prop.custom = v->asBool();
    prop.metadata = composeMetadata(specs, isStructuralPropertyField);
    std::string composedPath = path::property(prim.path, name);
    if (prop.isRelationship) {
      prop.targets = composePaths(index, name, field::kTargetPaths, composedPath);
    } else {
      detail::ResolvedValue resolved = detail::resolveAttributeValue(index, name, stage_.timeCode);
      prop.value = std::move(resolved.value);
      prop.fromTimeSamples = resolved.fromTimeSamples;
      prop.samples = std::move(resolved.samples);
      if (resolved.layer) prop.valueLayer = resolved.layer->identifier;
      if (prop.value.kind == Kind::AssetPath)
        for (const std::string& asset : prop.value.strings)
          prop.resolvedAssets.push_back(asset.empty() ? std::string() : resolveAssetPath(asset, prop.valueLayer));
      prop.connections = composePaths(index, name, field::kConnectionPaths, composedPath);
    }
    prim.properties.push_back(std::move(prop));
  }
}

void Composer::checkOverridesUsed() const {
  const auto& used = builder_->usedOverrides();
  for (const auto& [primPath, sets] : options_.variantOverrides)
    for (const auto& [set, variant] : sets)
      if (std::find(used.begin(), used.end(), primPath + "\n" + set) == used.end()) {
        const ComposedPrim* prim = stage_.prim(primPath);
        throw VariantOverrideError(primPath, set,
                                   "variant override " + primPath + " " + set + "=" + variant + ": " +
                                       (prim ? "the prim has no variant set '" + set + "'"
                                             : "there is no prim " + primPath + " in the stage"));
      }
}

ComposedStage composeStage(const std::string& rootIdentifier, const LayerReader& reader, const ComposeOptions& options) {
  // The same form resolved asset paths have, so that a layer reached both
  // ways is one layer.
  Composer composer(resolveAssetPath(rootIdentifier, ""), reader, options);
  return composer.run();
}

}  // namespace sdg::usd
