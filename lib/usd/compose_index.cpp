// Composition: building a prim's index, the graph of sites that hold its
// opinions. A prim's index starts from its parent's (every site extended by
// the prim's name: ancestral arcs), then each site's own arcs are added —
// inherits, references, payloads, specializes — recursively, and variant
// sets last, one at a time from the strongest site, since a selection may
// be written anywhere in the index, even inside another variant.
#include <algorithm>

#include "usd/asset_paths.h"
#include "usd/compose_internal.h"
#include "usd/layer_io.h"
#include "usd/sdf_path.h"

namespace sdg::usd {

const char* arcTypeName(ArcType arc) {
  switch (arc) {
    case ArcType::Root: return "root";
    case ArcType::Inherit: return "inherit";
    case ArcType::Variant: return "variant";
    case ArcType::Reference: return "reference";
    case ArcType::Payload: return "payload";
    case ArcType::Specialize: return "specialize";
  }
  return "?";
}

namespace detail {

namespace {

bool stackHasSpec(const LayerStack& stack, const std::string& path) {
  for (const Layer* layer : stack.layers)
    if (layer->spec(path)) return true;
  return false;
}

// Sibling strength: arc type, then the deeper namespace the arc was added
// at, then the order written.
bool strongerSibling(const Node& a, const Node& b) {
  if (a.arc != b.arc) return a.arc < b.arc;
  if (a.namespaceDepth != b.namespaceDepth) return a.namespaceDepth > b.namespaceDepth;
  return a.siblingNumber < b.siblingNumber;
}

bool isUsdLayerPath(const std::string& resolved) {
  std::string inner = splitPackagePathInner(resolved).second;  // the innermost entry of nested packages
  std::string name = inner.empty() ? resolved : inner;
  size_t dot = name.rfind('.');
  std::string ext = dot == std::string::npos ? "" : name.substr(dot);
  return ext == ".usd" || ext == ".usda" || ext == ".usdc" || ext == ".usdz";
}

// Where the spec at `path` was written (the arcs found there name it in errors).
SourceLoc specLoc(const Layer& layer, const std::string& path) {
  const Spec* spec = layer.spec(path);
  return spec ? spec->loc : SourceLoc(layer.identifier, 0, 0);
}

std::string describeReference(const Reference& ref, bool payload) {
  std::string out = payload ? "payload " : "reference ";
  if (!ref.assetPath.empty()) out += "@" + ref.assetPath + "@";
  if (!ref.primPath.empty()) out += "<" + ref.primPath + ">";
  return out;
}

}  // namespace

void PrimIndex::computeOrder() {
  order.clear();
  std::vector<int> stack{0};
  while (!stack.empty()) {
    int n = stack.back();
    stack.pop_back();
    order.push_back(n);
    const auto& kids = nodes[static_cast<size_t>(n)].children;
    for (auto it = kids.rbegin(); it != kids.rend(); ++it) stack.push_back(*it);
  }
}

std::optional<std::string> PrimIndex::mapToRoot(const Node& node, const std::string& p) const {
  std::string current = path::stripVariants(p);
  for (const MapFunction* map : node.mapsToRoot) {
    std::optional<std::string> next = map->map(current);
    if (!next) return std::nullopt;
    current = std::move(*next);
  }
  return current;
}

int IndexBuilder::addNode(PrimIndex& index, int parent, Node node, std::shared_ptr<const MapFunction> map, int chainFrom) {
  if (index.nodes.size() >= options_.limits.maxArcsPerPrim)
    throw usdErrorAt(node.arcLoc, "more than " + std::to_string(options_.limits.maxArcsPerPrim) +
                                      " composition arcs for one prim, the limit");
  int arcDepth = 0;
  for (int a = parent; a >= 0; a = index.nodes[static_cast<size_t>(a)].parent) ++arcDepth;
  if (static_cast<uint32_t>(arcDepth) > options_.limits.maxArcDepth)
    throw usdErrorAt(node.arcLoc, "composition arcs nested deeper than " +
                                      std::to_string(options_.limits.maxArcDepth) + ", the limit");
  const Node& from = index.nodes[static_cast<size_t>(chainFrom >= 0 ? chainFrom : parent)];
  node.parent = parent;
  node.mapsToRoot.clear();
  if (map) node.mapsToRoot.push_back(map.get());
  node.mapsToRoot.insert(node.mapsToRoot.end(), from.mapsToRoot.begin(), from.mapsToRoot.end());
  if (map) index.maps.push_back(std::move(map));
  node.hasSpecs = stackHasSpec(*node.stack, node.path);
  int id = static_cast<int>(index.nodes.size());
  index.nodes.push_back(std::move(node));
  auto& kids = index.nodes[static_cast<size_t>(parent)].children;
  const Node& added = index.nodes.back();
  auto at = std::find_if(kids.begin(), kids.end(), [&](int k) { return strongerSibling(added, index.nodes[static_cast<size_t>(k)]); });
  kids.insert(at, id);
  return id;
}

void IndexBuilder::checkCycle(const PrimIndex& index, int parent, const LayerStack* stack, const std::string& p,
                              const SourceLoc& at, const std::string& arcText) const {
  std::string target = path::stripVariants(p);
  for (int a = parent; a >= 0; a = index.nodes[static_cast<size_t>(a)].parent) {
    const Node& node = index.nodes[static_cast<size_t>(a)];
    if (node.stack != stack) continue;
    std::string site = path::stripVariants(node.path);
    if (path::hasPrefix(site, target) || path::hasPrefix(target, site))
      throw usdErrorAt(at, arcText + " makes a composition cycle: <" + target + "> in " + stack->identifier +
                               " leads back to <" + site + ">");
  }
}

PrimIndex IndexBuilder::build(const std::string& primPath, const PrimIndex* parentIndex) {
  PrimIndex index;
  if (!parentIndex) {
    Node root;
    root.stack = &rootStack_;
    root.path = primPath;
    root.hasSpecs = stackHasSpec(rootStack_, primPath);
    index.nodes.push_back(std::move(root));
  } else {
    index.nodes = parentIndex->nodes;
    index.maps = parentIndex->maps;
    std::string_view name = path::name(primPath);
    for (Node& node : index.nodes) {
      node.path = path::child(node.path, name);
      node.arcsDone = false;
      node.variantSetsDone = 0;
      node.variantsDone = false;
      node.hasSpecs = stackHasSpec(*node.stack, node.path);
    }
  }
  while (true) {
    bool expanded = false;
    for (size_t i = 0; i < index.nodes.size(); ++i) {
      if (index.nodes[i].arcsDone) continue;
      expandArcs(index, static_cast<int>(i), primPath);
      expanded = true;
    }
    if (!expanded && !expandVariants(index, primPath)) break;
  }
  index.computeOrder();
  return index;
}

void IndexBuilder::expandArcs(PrimIndex& index, int n, const std::string& primPath) {
  index.nodes[static_cast<size_t>(n)].arcsDone = true;
  if (!index.nodes[static_cast<size_t>(n)].hasSpecs) return;
  addClassArcs(index, n, primPath, false);
  addReferenceArcs(index, n, primPath, false);
  addReferenceArcs(index, n, primPath, true);
  addClassArcs(index, n, primPath, true);
}

void IndexBuilder::addReferenceArcs(PrimIndex& index, int n, const std::string& primPath, bool payload) {
  const LayerStack* stack = index.nodes[static_cast<size_t>(n)].stack;
  const std::string site = index.nodes[static_cast<size_t>(n)].path;
  const LayerOffset siteOffset = index.nodes[static_cast<size_t>(n)].offsetToRoot;
  auto items = composeReferenceListOp(*stack, site, payload ? field::kPayload : field::kReferences);
  for (size_t k = 0; k < items.size(); ++k) {
    const Reference& ref = items[k].item;
    const Layer& authoring = *stack->layers[items[k].layerIndex];
    SourceLoc at = ref.loc.known() ? ref.loc : specLoc(authoring, site);
    std::string arcText = describeReference(ref, payload);
    bool internal = ref.assetPath.empty();
    const LayerStack* target = stack;
    if (!internal) {
      std::string resolved = resolveAssetPath(ref.assetPath, authoring.identifier);
      if (!isUsdLayerPath(resolved)) {  // MaterialX and other formats USD reads through plugins
        warnings_.push_back({at, "reference to a non-USD file",
                             at.str() + ": " + arcText + ": not a USD layer (.usd, .usda, .usdc, .usdz); ignored"});
        continue;
      }
      target = &cache_.stack(resolved, at, arcText);
    }
    std::string targetPath = ref.primPath;
    if (targetPath.empty()) {
      const Value* defaultPrim = target->layers.front()->pseudoRoot().field(field::kDefaultPrim);
      if (!defaultPrim || !isText(defaultPrim->kind) || defaultPrim->asString().empty())
        throw usdErrorAt(at, arcText + ": " + target->identifier +
                                 " has no defaultPrim; name the prim to " + (payload ? "load" : "reference") + " (@" +
                                 ref.assetPath + "@</Prim>)");
      targetPath = defaultPrim->asString();
      if (targetPath[0] != '/') targetPath = "/" + targetPath;
    }
    if (!stackHasSpec(*target, targetPath))
      throw usdErrorAt(at, arcText + ": no prim <" + targetPath + "> in " + target->identifier);
    checkCycle(index, n, target, targetPath, at, arcText);
    MapFunction mapping{{{path::stripVariants(targetPath), path::stripVariants(site)}}};
    // Internal arcs stay in one namespace: paths outside the referenced
    // prim keep their meaning (USD 23.05 and later).
    if (internal) mapping.pairs.emplace_back("/", "/");
    auto map = std::make_shared<const MapFunction>(std::move(mapping));
    Node child;
    child.stack = target;
    child.path = targetPath;
    child.arc = payload ? ArcType::Payload : ArcType::Reference;
    child.namespaceDepth = path::depth(primPath);
    child.siblingNumber = static_cast<int>(k);
    child.arcLoc = at;
    child.internal = internal;
    child.offsetToRoot = concat(siteOffset, concat(stack->offsets[items[k].layerIndex], ref.offset));
    addNode(index, n, std::move(child), std::move(map));
  }
}

void IndexBuilder::addClassArcs(PrimIndex& index, int n, const std::string& primPath, bool specializes) {
  const Node origin = index.nodes[static_cast<size_t>(n)];  // a copy: adding nodes moves the vector
  auto items = composeTextListOp(*origin.stack, origin.path, specializes ? field::kSpecializes : field::kInheritPaths);
  std::string site = path::stripVariants(origin.path);
  for (size_t k = 0; k < items.size(); ++k) {
    const std::string& classPath = items[k].item;
    SourceLoc at = specLoc(*origin.stack->layers[items[k].layerIndex], origin.path);
    std::string arcText = std::string(specializes ? "specializes" : "inherits") + " <" + classPath + ">";
    checkCycle(index, n, origin.stack, classPath, at, arcText);
    auto makeMap = [](const std::string& from, const std::string& to) {
      return std::make_shared<const MapFunction>(MapFunction{{{from, to}, {"/", "/"}}});
    };
    Node child;
    child.stack = origin.stack;
    child.path = classPath;
    child.arc = specializes ? ArcType::Specialize : ArcType::Inherit;
    child.namespaceDepth = path::depth(primPath);
    child.arcLoc = at;
    child.offsetToRoot = origin.offsetToRoot;
    if (!specializes) {
      child.siblingNumber = static_cast<int>(k);
      addNode(index, n, std::move(child), makeMap(classPath, site));
      addImpliedInherits(index, n, classPath, static_cast<int>(k), at);
      continue;
    }
    // Specializes are weaker than everything else in the index: the class
    // is placed under the root, after all its other arcs, mapping through
    // its origin. A class written in another layer stack also brings the
    // root layer stack's opinions at the class's path in the root
    // namespace, just stronger than the class itself.
    int sibling = static_cast<int>(2 * k + 1);
    if (n != 0 && origin.stack != &rootStack_) {
      if (std::optional<std::string> implied = index.mapToRoot(origin, classPath);
          implied && stackHasSpec(rootStack_, *implied)) {
        Node local = child;
        local.stack = &rootStack_;
        local.path = *implied;
        local.siblingNumber = sibling - 1;
        local.offsetToRoot = LayerOffset{};
        addNode(index, 0, std::move(local), makeMap(*implied, *implied), 0);
      }
    }
    child.siblingNumber = sibling;
    addNode(index, 0, std::move(child), makeMap(classPath, site), n);
  }
}

// A class inherited inside a referenced asset is also looked up in each
// referencing layer stack, at the class's path mapped into it, as USD
// does: a stage can override the classes of the assets it references.
void IndexBuilder::addImpliedInherits(PrimIndex& index, int n, const std::string& classPath, int sibling,
                                      const SourceLoc& at) {
  std::string mapped = classPath;
  for (int cur = n; index.nodes[static_cast<size_t>(cur)].parent >= 0;) {
    const Node& node = index.nodes[static_cast<size_t>(cur)];
    if (node.mapsToRoot.empty()) return;
    // Classes cross a reference's mapping by identity where the mapping
    // does not cover them (a root class such as </_Look> stays </_Look>).
    std::optional<std::string> up = node.mapsToRoot.front()->map(mapped);
    if (!up) up = path::stripVariants(mapped);
    int parent = node.parent;
    const Node& into = index.nodes[static_cast<size_t>(parent)];
    if (into.stack != node.stack && stackHasSpec(*into.stack, *up)) {
      bool present = std::any_of(into.children.begin(), into.children.end(), [&](int k) {
        const Node& c = index.nodes[static_cast<size_t>(k)];
        return c.stack == into.stack && c.path == *up;
      });
      if (!present) {
        Node implied;
        implied.stack = into.stack;
        implied.path = *up;
        implied.arc = ArcType::Inherit;
        implied.namespaceDepth = node.namespaceDepth;
        implied.siblingNumber = sibling;
        implied.arcLoc = at;
        implied.offsetToRoot = into.offsetToRoot;
        auto map = std::make_shared<const MapFunction>(
            MapFunction{{{*up, path::stripVariants(into.path)}, {"/", "/"}}});
        addNode(index, parent, std::move(implied), std::move(map));
      }
    }
    mapped = *up;
    cur = parent;
  }
}

std::string IndexBuilder::findSelection(const PrimIndex& index, const std::string& set) const {
  for (int n : index.order) {
    const Node& node = index.nodes[static_cast<size_t>(n)];
    if (!node.hasSpecs) continue;
    for (const Layer* layer : node.stack->layers) {
      const Spec* spec = layer->spec(node.path);
      if (!spec) continue;
      const Value* selections = spec->field(field::kVariantSelection);
      if (!selections || !selections->dictionary) continue;
      auto it = selections->dictionary->find(set);
      if (it != selections->dictionary->end() && isText(it->second.kind) && !it->second.isArray)
        return it->second.asString();
    }
  }
  return "";
}

// Evaluates the next variant set of the strongest site that has one left.
// Returns whether anything changed (then arcs are expanded again).
bool IndexBuilder::expandVariants(PrimIndex& index, const std::string& primPath) {
  index.computeOrder();
  for (int n : index.order) {
    Node& node = index.nodes[static_cast<size_t>(n)];
    if (node.variantsDone) continue;
    if (!node.hasSpecs) {
      node.variantsDone = true;
      continue;
    }
    auto sets = composeTextListOp(*node.stack, node.path, field::kVariantSetNames);
    if (static_cast<size_t>(node.variantSetsDone) >= sets.size()) {
      node.variantsDone = true;
      continue;
    }
    const std::string set = sets[static_cast<size_t>(node.variantSetsDone)].item;
    ++node.variantSetsDone;
    std::string selection;
    bool overridden = false;
    if (auto prim = options_.variantOverrides.find(primPath); prim != options_.variantOverrides.end()) {
      if (auto chosen = prim->second.find(set); chosen != prim->second.end()) {
        selection = chosen->second;
        overridden = true;
        usedOverrides_.push_back(primPath + "\n" + set);
      }
    }
    if (!overridden) selection = findSelection(index, set);
    bool recorded = std::any_of(index.selections.begin(), index.selections.end(),
                                [&](const auto& s) { return s.first == set; });
    if (!recorded) index.selections.emplace_back(set, selection);
    if (selection.empty()) return true;
    std::string variantPath = path::variant(node.path, set, selection);
    const Node site = node;  // a copy: adding nodes moves the vector
    if (!stackHasSpec(*site.stack, variantPath)) {
      std::vector<std::string> offered;
      forEachSpec(*site.stack, path::variantSet(site.path, set), [&](const Spec& spec, size_t) {
        if (const Value* v = spec.field(field::kVariantChildren))
          for (const std::string& name : v->strings)
            if (std::find(offered.begin(), offered.end(), name) == offered.end()) offered.push_back(name);
      });
      std::string message = primPath + ": variant set '" + set + "' has no variant '" + selection + "'" +
                            (offered.empty() ? std::string(" (it offers none)")
                                             : " (it offers " + [&] {
                                                 std::string list;
                                                 for (const std::string& o : offered) list += (list.empty() ? "" : ", ") + o;
                                                 return list;
                                               }() + ")");
      if (overridden) throw VariantOverrideError(primPath, set, "variant override " + message);
      warnings_.push_back({SourceLoc(), "variant selection naming no variant", message + "; no variant applied"});
      return true;
    }
    Node variant;
    variant.stack = site.stack;
    variant.path = variantPath;
    variant.arc = ArcType::Variant;
    variant.namespaceDepth = path::depth(primPath);
    variant.siblingNumber = site.variantSetsDone - 1;
    variant.offsetToRoot = site.offsetToRoot;
    forEachSpec(*site.stack, site.path, [&](const Spec& spec, size_t) {
      if (!variant.arcLoc.known()) variant.arcLoc = spec.loc;
    });
    addNode(index, n, std::move(variant), nullptr);
    return true;
  }
  return false;
}

}  // namespace detail
}  // namespace sdg::usd
