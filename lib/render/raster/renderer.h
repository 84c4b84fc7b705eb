#pragma once
// Draws a RenderList through a GlContext into framebuffer objects and reads
// back the passes asked for. Meshes and textures are uploaded once and
// reused across frames; shader programs and FBOs live as long as the
// renderer.
#include <map>
#include <memory>
#include <string>
#include <unordered_map>

#include <array>

#include "assets/asset_resolver.h"
#include "assets/image.h"
#include "assets/mesh_data.h"
#include "render/coverage_masks.h"
#include "render/frame_passes.h"
#include "render/lens_views.h"
#include "render/render_settings.h"
#include "render/raster/gl_context.h"
#include "render/raster/instance_batches.h"
#include "render/render_list.h"
#include "render/raster/shading_variant.h"

namespace sdg {

class Renderer {
 public:
  Renderer(GlContext& context, const AssetResolver& assets, const RenderSettings& settings);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders camera `cameraIndex` of `list` into `out` (resized as needed).
  // Asset problems (missing or corrupt mesh or texture) throw RunError
  // naming the prim and the file.
  void render(const RenderList& list, size_t cameraIndex, FramePasses& out, const PassSelection& passes = {});

  // The same in two halves, so a run can overlap the GPU with the CPU:
  // queue() draws and starts the read-back into pixel buffer objects of
  // `slot` (0 or 1) without waiting for the GPU; collect() waits for that
  // slot and fills `out`, bit for bit what render() would have. With
  // subframes > 1 queue() renders synchronously and collect() hands over.
  void queue(const RenderList& list, size_t cameraIndex, const PassSelection& passes, int slot);
  void collect(int slot, FramePasses& out);
  const RenderSettings& settings() const { return settings_; }

  // For each group of items (an entity), drawn alone with the same camera:
  // how many pixels it covers and its pixel bounds (inclusive; empty when it
  // covers none). Exact, unlike projecting bounding boxes.
  using Coverage = MaskCoverage;
  // The masks as read back (render/coverage_masks.h).
  using CoverageMasks = sdg::CoverageMasks;
  // Draws the masks and starts their read-back into `slot` (as queue());
  // collectCoverage() waits for them. coverageOf() turns them into pixel
  // counts and bounds: CPU work that a writer thread can take.
  void queueCoverage(const RenderList& list, size_t cameraIndex, const std::vector<std::vector<size_t>>& groups,
                     int slot);
  void collectCoverage(int slot, CoverageMasks& out);
  static void coverageOf(const CoverageMasks& masks, std::vector<Coverage>& out);
  // Issues every draw a frame of `list` makes (with coverage masks of
  // `coverageGroups` when given), from the camera moved just past the
  // scene so that nothing reaches a pixel, and reads the result back
  // through slot 0. llvmpipe compiles a shader variant at its first draw,
  // so this compiles what such frames need for a fraction of a frame's
  // cost; the output is discarded and later frames are unchanged.
  void compileFor(const RenderList& list, size_t cameraIndex, const PassSelection& passes,
                  const std::vector<std::vector<size_t>>* coverageGroups);
  // Local bounds of an item's mesh (loads it if needed).
  Eigen::AlignedBox3f meshBounds(const RenderItem& item);

 private:
  struct GpuMesh;
  struct Uniforms;
  struct ShadowSlot {
    size_t light = 0;
    Matrix4d viewProjection = Matrix4d::Identity();
  };
  struct GpuTexture {
    unsigned id = 0;
  };
  const GpuMesh& mesh(const RenderItem& item);
  // meshSlots_[i] = the slot of list.items[i]'s mesh (loading it if needed).
  void resolveMeshes(const RenderList& list);
  // Uploads `batches`' records into `buffer` for this frame's draws.
  void uploadInstances(const InstanceBatches& batches, unsigned buffer);
  // Binds the batch's mesh with its instance attributes at the batch's
  // records in `buffer`.
  const GpuMesh& bindBatch(const InstanceBatch& batch, unsigned buffer);
  // Every index of a mesh's parts in one instanced draw (positions only),
  // for each batch of byMesh() but those `skip` marks.
  void drawWholeMeshes(const InstanceBatches& batches, unsigned buffer, const std::vector<uint8_t>* skip = nullptr);
  // The texture `key` names (a file as written in the scene, or an image
  // embedded in a mesh file), uploaded for use as colour or as data.
  const GpuTexture& texture(const std::string& key, const std::string& primPath, TextureData data);
  ImageRgba8 decodeTexture(const std::string& key, const std::string& primPath, TextureData data) const;
  // Binds the maps a part samples to their units (render/shaders.h).
  void bindMaps(const MaterialMaps& maps, const std::string& primPath);
  // The pre-filtered textures of a dome's map, made the first time.
  struct DomeTextures {
    unsigned background = 0, specular = 0, irradiance = 0;
    int specularLevels = 1;
  };
  const DomeTextures& dome(const RenderLight& light);
  // Marks in skipInDepth_ the batches of byMesh() that hold a cut-out.
  void markCutOutBatches(const RenderList& list);
  // The world bounds of every item into itemBounds_; returns their union.
  Eigen::AlignedBox3d sceneBounds(const RenderList& list);
  // Marks in skipInShadow_ the batches of byMesh() that `light`'s map can
  // leave out (render/shadow_casters.h).
  void markShadowlessBatches(const RenderLight& light, const Eigen::AlignedBox3d& scene);
  void drawShadowMaps(const RenderList& list, const RenderCamera& camera);
  int shadowMapSize() const;
  // Makes the scene program for this frame's lights and `variant` current,
  // compiling it the first time and giving it this frame's uniforms the
  // first time in a frame; returns its uniform locations.
  const Uniforms& sceneVariant(const ShadingVariant& variant);
  void uploadFrameUniforms(const Uniforms& u) const;
  Uniforms uniformsOf(unsigned program) const;
  void drawScene(const RenderList& list, const RenderCamera& camera, const Eigen::Vector2d& jitter);
  void readBack(FramePasses& out, bool colorOnly, const PassSelection& passes);
  void ensureTargets();
  void drawFrame(const RenderList& list, size_t cameraIndex, const PassSelection& passes);
  void drawFrame(const RenderList& list, const RenderCamera& camera, const PassSelection& passes);
  // A camera with a calibrated lens (render/lens_views.h): its pinhole
  // views drawn and read back one after another, then resampled into `out`.
  void renderLens(const RenderList& list, const RenderCamera& camera, FramePasses& out, const PassSelection& passes);
  void drawMaskLayers(const RenderList& list, const RenderCamera& camera, const std::vector<std::vector<size_t>>& groups,
                      unsigned buffer, uint32_t* cpu);
  // One attachment's pixels (bottom row first, as GL gives them) into `out`.
  void unpack(int attachment, const void* pixels, FramePasses& out);
  struct ReadSlot {
    unsigned buffers[4] = {0, 0, 0, 0};  // one pixel buffer per attachment
    PassSelection passes;
    bool pending = false;
    bool synchronous = false;  // subframes: the frame is already in `frame`
    FramePasses frame;
    unsigned maskBuffer = 0;  // coverage layers, one after another
    size_t maskBufferBytes = 0;
    size_t maskGroups = 0;
    bool masksPending = false;
    // A lens camera's masks, resampled from its views when queued.
    std::vector<uint32_t> lensMasks;
    bool lensMasksReady = false;
  };
  ReadSlot readSlots_[2];

  GlContext& context_;
  const GlApi& gl_;
  const AssetResolver& assets_;
  RenderSettings settings_;
  unsigned shadowProgram_ = 0, skyProgram_ = 0, maskProgram_ = 0, emptyVao_ = 0;
  unsigned depthProgram_ = 0;
  int depthViewProjection_ = -1;
  // This frame's items grouped for instanced draws, and the coverage pass's.
  InstanceBatches batches_, maskBatches_;
  unsigned instanceBuffer_ = 0, maskInstanceBuffer_ = 0;
  std::vector<uint32_t> meshSlots_;
  std::vector<const GpuMesh*> meshBySlot_;
  unsigned maskFramebuffer_ = 0, maskTexture_ = 0, maskDepth_ = 0;
  int maskWidth_ = 0, maskHeight_ = 0;
  // The scene program, compiled once per arrangement of lights (their types
  // and shadow slots become literals in the shader), and its uniforms.
  struct SceneProgram {
    unsigned program = 0;
    std::unique_ptr<Uniforms> uniforms;
  };
  std::map<std::string, SceneProgram> scenePrograms_;
  std::string lightCalls_;  // this frame's arrangement of lights and dome
  std::string variantKey_;  // lightCalls_ and a shading variant: a program's key
  // What every scene program of a frame is given, set once per frame.
  struct FrameUniforms {
    Eigen::Matrix4f viewProjection;
    float eye[3], forward[3], ambient[3], ambientSpecular[3];  // the untextured domes', per lobe
    float metersPerUnit = 1, shadowTexel = 0;
    float radiance[3 * 16], position[3 * 16], direction[3 * 16], params[4 * 16], response[2 * 16];
    float shadowMatrices[16 * 4];
    bool dome = false;
    Eigen::Matrix3f domeFromWorld;
    float domeLod = 0, domeScale[3], domeResponse[2] = {1, 1};
  };
  FrameUniforms frame_;
  // This frame's programs by ShadingVariant::index(), null until first used.
  std::array<const SceneProgram*, ShadingVariant::kCount> frameVariants_{};
  // compileFor(): the plain, UV-textured and triplanar programs are drawn
  // once, so textures that behaviors bind later find their program compiled.
  bool warmAllTextureModes_ = false;
  int shadowLightViewProjection_ = -1, maskViewProjection_ = -1;
  std::unique_ptr<Uniforms> skyUniforms_;
  unsigned framebuffer_ = 0, shadowFramebuffer_ = 0;
  unsigned colorTexture_ = 0, normalTexture_ = 0, planeTexture_ = 0, idTexture_ = 0, depthTexture_ = 0;
  unsigned whiteTexture_ = 0;
  unsigned brdfLut_ = 0;  // the split-sum table, made once
  unsigned shadowAtlas_ = 0;              // 2 x 2 tiles of shadowMapSize, made on first use
  std::vector<ShadowSlot> shadowSlots_;    // this frame's shadowed lights
  std::vector<Eigen::AlignedBox3d> itemBounds_;  // this frame's, by item
  std::vector<uint8_t> skipInShadow_;            // by batch of byMesh(), for one light
  std::vector<uint8_t> skipInDepth_;             // by batch of byMesh(): cut-outs, this frame
  std::unordered_map<std::string, std::unique_ptr<GpuMesh>> meshes_;
  std::unordered_map<std::string, GpuTexture> colorTextures_, dataTextures_;
  // Images embedded in the mesh files loaded so far, by texture key.
  std::unordered_map<std::string, EmbeddedImage> embeddedImages_;
  std::unordered_map<std::string, DomeTextures> domes_;
  // Lens cameras' view plans by camera path, and their views' passes.
  std::map<std::string, LensViewPlan> lensPlans_;
  std::vector<FramePasses> lensViews_;
  std::vector<uint32_t> lensMaskView_;  // one view's coverage masks
  std::vector<uint32_t> colorSum_;
  std::vector<uint8_t> scratchRgba_;
  std::vector<float> scratchFloat_;
};

}  // namespace sdg
