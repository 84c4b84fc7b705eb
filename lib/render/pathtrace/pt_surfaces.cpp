#include "render/pathtrace/pt_surfaces.h"

#include "assets/mesh_source.h"

namespace sdg {

bool PtSurfaces::opaqueAt(uint32_t instance, uint32_t triangle, float u, float v) const {
  const SurfaceGeometry g = scene->geometry(SurfaceHit{instance, triangle, u, v, 0.0f});
  return surfaceOpaque(material(instance, g.part), g);
}

void preparePtSurfaces(const RenderList& list, const AssetResolver& assets, PtGeometryCache& cache, PtSurfaces& out) {
  out.scene = &cache.scene;
  std::vector<SceneInstance> instances(list.items.size());
  for (size_t i = 0; i < list.items.size(); ++i) {
    const RenderItem& item = list.items[i];
    auto found = cache.meshes.find(item.meshId);
    if (found == cache.meshes.end()) {
      MeshData data = meshDataFor(item.mesh, assets, item.primPath);
      cache.textures.addEmbedded(data.embeddedImages);
      data.embeddedImages.clear();
      found = cache.meshes.emplace(item.meshId, cache.scene.addMesh(std::move(data))).first;
    }
    const MeshData& mesh = cache.scene.mesh(found->second);
    out.materialOffset.push_back(uint32_t(out.materials.size()));
    out.instanceIds.push_back(item.instanceId);
    bool cutOut = false;
    const std::vector<MeshPart> defaultPart(mesh.parts.empty() ? 1 : 0);
    for (const MeshPart& part : mesh.parts.empty() ? defaultPart : mesh.parts) {
      out.materials.push_back(resolveSurfaceMaterial(item, part, cache.textures));
      cutOut = cutOut || out.materials.back().cutOut();
    }
    out.partCount.push_back(uint32_t(out.materials.size() - out.materialOffset.back()));
    instances[i] = SceneInstance{found->second, item.worldFromLocal, cutOut};
    out.anyCutOut = out.anyCutOut || cutOut;
  }
  cache.scene.setInstances(instances);
}

}  // namespace sdg
