#include "render/raster/instance_batches.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace sdg {

namespace {

constexpr uint32_t kUnseen = std::numeric_limits<uint32_t>::max();

// What a shading batch shares: the material's source, its maps and
// projection (which pick the program and the bound textures) and the
// inputs set once per draw (normal strength, cut-out). Roughness, metallic,
// their influences and the base colour travel per instance.
auto batchKey(const RenderMaterial& m) {
  return std::tie(m.fromPrim, m.maps, m.projectUvw, m.opacity, m.normalScale, m.specularLevel, m.opacityConstant,
                  m.opacityCutoff, m.vertexColors);
}

bool sameMaterialSource(const RenderItem& a, const RenderItem& b) {
  return batchKey(a.material) == batchKey(b.material);
}

void fillRecord(const RenderItem& item, uint32_t id, InstanceRecord& r) {
  const Eigen::Matrix4f world = item.worldFromLocal.cast<float>();
  std::copy_n(world.data(), 16, r.worldFromLocal);
  const Eigen::Matrix3f normal = item.worldFromLocal.block<3, 3>(0, 0).inverse().transpose().cast<float>();
  std::copy_n(normal.data(), 9, r.normalMatrix);
  const RenderMaterial& m = item.material;
  for (int c = 0; c < 3; ++c) r.baseColor[c] = m.baseColor[c];
  r.surface[0] = m.roughness;
  r.surface[1] = m.metallic;
  r.surface[2] = m.roughnessInfluence;
  r.surface[3] = m.metallicInfluence;
  const double radians = double(m.textureRotate) * M_PI / 180.0;
  r.textureTransform[0] = m.textureScale.x();
  r.textureTransform[1] = m.textureScale.y();
  r.textureTransform[2] = float(std::cos(radians));
  r.textureTransform[3] = float(std::sin(radians));
  r.id = id;
}

}  // namespace

void InstanceBatches::build(const RenderList& list, const std::vector<uint32_t>& meshSlots) {
  items_.resize(list.items.size());
  ids_.resize(list.items.size());
  for (size_t i = 0; i < list.items.size(); ++i) {
    items_[i] = i;
    ids_[i] = list.items[i].instanceId;
  }
  arrange(list, meshSlots);
}

void InstanceBatches::buildMasks(const RenderList& list, const std::vector<uint32_t>& meshSlots,
                                 const std::vector<std::vector<size_t>>& groups, size_t first, size_t last) {
  items_.clear();
  ids_.clear();
  for (size_t g = first; g < last; ++g)
    for (size_t index : groups[g]) {
      items_.push_back(index);
      ids_.push_back(1u << (g - first));
    }
  arrange(list, meshSlots);
}

void InstanceBatches::arrange(const RenderList& list, const std::vector<uint32_t>& meshSlots) {
  // Each mesh ranks by the first candidate that uses it.
  uint32_t slots = 0;
  for (size_t index : items_) slots = std::max(slots, meshSlots[index] + 1);
  firstAppearance_.assign(slots, kUnseen);
  for (size_t k = 0; k < items_.size(); ++k) {
    uint32_t& seen = firstAppearance_[meshSlots[items_[k]]];
    if (seen == kUnseen) seen = uint32_t(k);
  }
  order_.resize(items_.size());
  for (size_t k = 0; k < order_.size(); ++k) order_[k] = uint32_t(k);
  std::stable_sort(order_.begin(), order_.end(), [&](uint32_t a, uint32_t b) {
    const size_t ia = items_[a], ib = items_[b];
    const uint32_t ra = firstAppearance_[meshSlots[ia]], rb = firstAppearance_[meshSlots[ib]];
    if (ra != rb) return ra < rb;
    return batchKey(list.items[ia].material) < batchKey(list.items[ib].material);
  });
  records_.resize(order_.size());
  byMesh_.clear();
  byMaterial_.clear();
  for (size_t k = 0; k < order_.size(); ++k) {
    const size_t index = items_[order_[k]];
    const RenderItem& item = list.items[index];
    fillRecord(item, ids_[order_[k]], records_[k]);
    const uint32_t slot = meshSlots[index];
    if (byMesh_.empty() || byMesh_.back().meshSlot != slot) byMesh_.push_back({uint32_t(k), 0, slot, index});
    ++byMesh_.back().count;
    if (byMaterial_.empty() || byMaterial_.back().meshSlot != slot ||
        !sameMaterialSource(list.items[byMaterial_.back().item], item))
      byMaterial_.push_back({uint32_t(k), 0, slot, index});
    ++byMaterial_.back().count;
  }
}

}  // namespace sdg
