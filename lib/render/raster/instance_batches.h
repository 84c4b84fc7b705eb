#pragma once
// Groups a frame's render items for instanced drawing: one draw call per
// mesh (per mesh part and material source when shading) instead of one per
// item, which is what makes 10,000 objects affordable on llvmpipe, where a
// draw call costs 3-4 microseconds of driver time in every pass.
//
// The order depends only on the list itself (where each mesh first appears,
// then the material's source, texture and projection), never on what was
// loaded before, so every frame and every shard of a run draws a scene the
// same way.
#include <cstdint>
#include <vector>

#include "render/render_list.h"

namespace sdg {

// One instance as the vertex shaders read it (attributes 3-13, divisor 1).
struct InstanceRecord {
  float worldFromLocal[16];  // column-major
  float normalMatrix[9];     // inverse transpose of the upper 3 x 3, column-major
  float baseColor[3];
  float surface[4];          // roughness, metallic and their maps' influences
  float textureTransform[4]; // scale x, scale y, cos and sin of the rotation
  uint32_t id;               // instance id, or the coverage bit
};
static_assert(sizeof(InstanceRecord) == 37 * 4, "the vertex attribute offsets assume a packed record");

// A run of records that share a mesh (and, for shading batches, a material
// source, maps and projection); `item` is the first of them, for the material.
struct InstanceBatch {
  uint32_t first = 0;
  uint32_t count = 0;
  uint32_t meshSlot = 0;
  size_t item = 0;
};

class InstanceBatches {
 public:
  // Every item of `list`, ids = instance ids. meshSlots[i] names the mesh of
  // list.items[i] (any small integer per distinct mesh).
  void build(const RenderList& list, const std::vector<uint32_t>& meshSlots);
  // Only the items of groups[first, last), ids = 1 << (group - first): the
  // coverage pass, which ORs every group's bit into one mask.
  void buildMasks(const RenderList& list, const std::vector<uint32_t>& meshSlots,
                  const std::vector<std::vector<size_t>>& groups, size_t first, size_t last);

  const std::vector<InstanceRecord>& records() const { return records_; }
  const std::vector<InstanceBatch>& byMesh() const { return byMesh_; }
  // Sub-runs of byMesh(): records whose material comes from the same source.
  const std::vector<InstanceBatch>& byMaterial() const { return byMaterial_; }

 private:
  void arrange(const RenderList& list, const std::vector<uint32_t>& meshSlots);

  // Candidates (item index, id) before sorting; kept between frames so a
  // steady run does not allocate.
  std::vector<size_t> items_;
  std::vector<uint32_t> ids_;
  std::vector<uint32_t> order_;
  std::vector<uint32_t> firstAppearance_;
  std::vector<InstanceRecord> records_;
  std::vector<InstanceBatch> byMesh_, byMaterial_;
};

}  // namespace sdg
