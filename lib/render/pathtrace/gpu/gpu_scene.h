#pragma once
// What the GPU path tracer uploads, packed on the CPU in the kernel's
// std430 layouts (shaders/pt_scene.glsl, pt_lights.glsl):
// - meshes: each distinct mesh's vertices, triangles and BVH, built and
//   packed once when it first appears and appended (a stage change adds
//   meshes, it does not repack the others);
// - the frame: instances (their transforms) and the top-level BVH over
//   them, rebuilt only when an instance moved, appeared or left; the
//   materials and lights (a few hundred bytes); textures and the dome map
//   appended when new.
// The `*Changed` flags tell the tracer which buffers to upload again.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "assets/asset_resolver.h"
#include "render/pathtrace/gpu/gpu_bvh.h"
#include "render/pathtrace/pt_lights.h"
#include "render/pathtrace/pt_materials.h"
#include "render/pathtrace/pt_textures.h"
#include "render/render_list.h"

namespace sdg {

struct GpuMeshRecord {
  int32_t bases[4];  // nodes, leaf-order triangles, indices, vertices
  int32_t flags[4];  // has normals, has uvs, root link, vertex colours (first vec4 of `vertices` + 1; 0: none)
};
struct GpuInstanceRecord {
  float world[12], local[12], normal[12];  // three rows of four each
  int32_t ids[4];                          // mesh, first material, material count, instance id
  int32_t flags[4];                        // cut-out
};
struct GpuMaterialRecord {
  float baseColor[4], scalars[4], opacity[4], placement[4];
  int32_t maps[4], mapInfo[4], modes[4];
};
struct GpuLightRecord {
  int32_t info[4];
  float radiancePick[4], positionRadius[4], axisXWidth[4], axisYHeight[4], axisZLength[4], emitArea[4],
      toLightCone[4], misc[4], mapScale[4], ambient[4], domeFromWorld[12];
};

// What a frame's stage uses that the tracing kernel can be compiled
// without (pt_common.glsl's SDG_* switches): a kernel holds the code of
// the features set only.
enum GpuKernelFeature : uint32_t {
  kGpuDomeMaps = 1u << 0,          // a dome light with a map
  kGpuOpacity = 1u << 1,           // a material with an opacity (cut-outs)
  kGpuNormalMaps = 1u << 2,        // a material with a normal map
  kGpuTriplanar = 1u << 3,         // a material projected triplanar
  kGpuLobeMultipliers = 1u << 4,   // a light's inputs:diffuse or inputs:specular not 1
  kGpuSphereLights = 1u << 5,      // a sphere light
  kGpuShapeLights = 1u << 6,       // a rect, disk or cylinder light
  kGpuDistantLights = 1u << 7,     // a distant light
  kGpuDomeLights = 1u << 8,        // a dome light
  kGpuBaseColorMaps = 1u << 9,     // a material with a base colour map
  kGpuSurfaceMaps = 1u << 10,      // a material with a roughness or metallic map
  kGpuVertexColors = 1u << 11,     // a material that multiplies by the mesh's vertex colours
  kGpuAllFeatures = (1u << 12) - 1,
};

class GpuSceneData {
 public:
  explicit GpuSceneData(const AssetResolver& assets);
  ~GpuSceneData();

  // Brings everything up to date with `list`; RunError for unreadable assets.
  void update(const RenderList& list);

  // Meshes (append-only).
  std::vector<GpuBvhNode> meshNodes;
  std::vector<float> triangles;  // 16 per triangle: the unit-triangle map's rows u, v, z; the triangle's index
  // 8 per vertex: position, u, normal, v; then, for a mesh with vertex
  // colours only, 4 per vertex (rgb, opacity), padded to whole 8s.
  std::vector<float> vertices;
  std::vector<uint32_t> indices; // 4 per triangle: vertex indices, part
  std::vector<GpuMeshRecord> meshes;
  bool meshesChanged = false;
  // The frame.
  std::vector<GpuBvhNode> topNodes;
  int32_t topRoot = 0;
  std::vector<GpuInstanceRecord> instances;  // in the top level's leaf order
  bool instancesChanged = false;
  std::vector<GpuMaterialRecord> materials;
  std::vector<GpuLightRecord> lights;
  bool anyLobeMultiplier = false;  // PtLights::anyLobeMultiplier()
  // Textures: a table of (first texel, width, height, sRGB) and the texels
  // (RGBA8 words), then the dome map's texels (4 float words each), uploaded
  // one after the other.
  std::vector<int32_t> textureTable;
  std::vector<uint32_t> texels;
  std::vector<float> domeTexels;
  bool texelsChanged = false;
  // The float tables: the sRGB decode, the lights' pick cdf, the dome's sampling tables.
  std::vector<float> tables;
  bool tablesChanged = true;  // beyond the pick cdf at the end, which changes every frame
  int32_t dome[4] = {0, 0, 0, 0};        // width, height, first texel word, pick cdf offset
  int32_t domeTables[4] = {0, 0, 0, 0};  // row cdf, column cdfs, row cosines, texel solid angles
  Eigen::AlignedBox3f bounds;
  uint32_t kernelFeatures = 0;  // GpuKernelFeature bits of this frame's stage

 private:
  struct Mesh;
  uint32_t meshFor(const RenderItem& item);
  int32_t textureIndex(const PtTexture* texture);
  void packLights(const RenderList& list);
  uint32_t featuresInUse() const;

  const AssetResolver& assets_;
  GpuBvhBuilder builder_;
  PtTextureCache textureCache_;
  std::map<std::string, uint32_t> meshIndex_;  // RenderItem::meshId -> mesh
  std::vector<std::unique_ptr<Mesh>> meshData_;
  std::map<const PtTexture*, int32_t> textureSlots_;
  std::map<std::string, std::unique_ptr<PtDomeMap>> domes_;
  const PtDomeMap* uploadedDome_ = nullptr;
  std::vector<double> lastTransforms_;  // the instances the top level was built for
};

}  // namespace sdg
