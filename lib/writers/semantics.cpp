#include "writers/semantics.h"

#include <algorithm>
#include <unordered_map>

namespace sdg {

namespace {
// Labels of `prim` and its ancestors, ancestor first, filtered by taxonomy.
LabelSet inheritedLabels(const Prim& prim, const std::vector<std::string>& types) {
  std::vector<const Prim*> chain;
  for (const Prim* p = &prim; p && !p->isPseudoRoot(); p = p->parent()) chain.push_back(p);
  LabelSet labels;
  for (auto it = chain.rbegin(); it != chain.rend(); ++it)
    for (const auto& [taxonomy, values] : (*it)->semantics()) {
      if (std::find(types.begin(), types.end(), taxonomy) == types.end()) continue;
      for (const std::string& v : values) {
        std::string& joined = labels[taxonomy];
        joined += (joined.empty() ? "" : ",") + v;
      }
    }
  return labels;
}

bool hasLabels(const Prim& prim, const std::vector<std::string>& types) {
  for (const auto& [taxonomy, values] : prim.semantics())
    if (!values.empty() && std::find(types.begin(), types.end(), taxonomy) != types.end()) return true;
  return false;
}
}  // namespace

FrameSemantics computeSemantics(const Stage& stage, const RenderList& list,
                                const std::vector<std::string>& semanticTypes) {
  FrameSemantics out;
  out.semanticLabels = {{{"class", "BACKGROUND"}}, {{"class", "UNLABELLED"}}};
  std::unordered_map<std::string, size_t> entityByPath;
  std::map<LabelSet, uint32_t> semanticIdByLabels;
  uint32_t maxRenderId = 0;
  for (const RenderItem& item : list.items) maxRenderId = std::max(maxRenderId, item.instanceId);
  out.entityOfRenderId.assign(size_t(maxRenderId) + 1, 0);

  for (size_t i = 0; i < list.items.size(); ++i) {
    const Prim* prim = stage.find(list.items[i].primPath);
    // The entity root: the nearest labelled prim at or above the geometry.
    const Prim* root = nullptr;
    for (const Prim* p = prim; p && !p->isPseudoRoot(); p = p->parent())
      if (hasLabels(*p, semanticTypes)) {
        root = p;
        break;
      }
    if (!root) continue;
    auto [it, inserted] = entityByPath.emplace(root->path(), out.entities.size());
    if (inserted) {
      SemanticEntity entity;
      entity.primPath = root->path();
      entity.labels = inheritedLabels(*root, semanticTypes);
      auto [sid, fresh] = semanticIdByLabels.emplace(entity.labels, uint32_t(out.semanticLabels.size()));
      if (fresh) out.semanticLabels.push_back(entity.labels);
      entity.semanticId = sid->second;
      entity.instanceId = uint32_t(out.entities.size()) + 2;
      entity.worldFromRoot = stage.worldMatrix(*root);
      out.entities.push_back(std::move(entity));
    }
    out.entities[it->second].items.push_back(i);
    out.entityOfRenderId[list.items[i].instanceId] = uint32_t(it->second) + 1;
  }
  return out;
}

}  // namespace sdg
