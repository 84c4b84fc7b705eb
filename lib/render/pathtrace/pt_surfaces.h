#pragma once
// A frame's surfaces as the CPU tracers see them (the path tracer and the
// LiDAR caster): the Embree scene of the render list's items, each mesh
// loaded and its BVH built once per cache, and per instance its parts'
// materials and render id. Also the cut-out test Embree's filters call.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "assets/asset_resolver.h"
#include "render/pathtrace/embree_scene.h"
#include "render/pathtrace/pt_materials.h"
#include "render/pathtrace/pt_textures.h"
#include "render/render_list.h"

namespace sdg {

// What stays loaded from frame to frame: meshes (with their BVHs) and textures.
struct PtGeometryCache {
  explicit PtGeometryCache(const AssetResolver& assets) : textures(assets) {}
  EmbreeScene scene;
  PtTextureCache textures;
  std::map<std::string, uint32_t> meshes;  // RenderItem::meshId -> EmbreeScene mesh
};

struct PtSurfaces : CutOutTest {
  const EmbreeScene* scene = nullptr;
  std::vector<uint32_t> materialOffset;  // per instance, into `materials`
  std::vector<uint32_t> partCount;       // per instance
  std::vector<uint32_t> instanceIds;     // per instance: RenderItem::instanceId
  std::vector<SurfaceMaterial> materials;
  bool anyCutOut = false;

  const SurfaceMaterial& material(uint32_t instance, uint32_t part) const {
    return materials[materialOffset[instance] + std::min(part, partCount[instance] - 1)];
  }
  bool opaqueAt(uint32_t instance, uint32_t triangle, float u, float v) const override;
  const CutOutTest* cutOuts() const { return anyCutOut ? this : nullptr; }
};

// Loads what `list`'s items need into `cache` (throws RunError for a mesh
// or texture that cannot be read), sets the cache scene's instances to the
// list's items (instance i = item i) and fills `out` (which must be empty).
void preparePtSurfaces(const RenderList& list, const AssetResolver& assets, PtGeometryCache& cache, PtSurfaces& out);

}  // namespace sdg
