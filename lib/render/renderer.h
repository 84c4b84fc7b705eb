#pragma once
// Draws a RenderList through a GlContext into framebuffer objects and reads
// back every pass. Meshes and textures are uploaded once and reused across
// frames; shader programs and FBOs live as long as the renderer.
#include <memory>
#include <string>
#include <unordered_map>

#include "assets/asset_resolver.h"
#include "assets/mesh_data.h"
#include "render/frame_passes.h"
#include "render/gl_context.h"
#include "render/render_list.h"

namespace sdg {

struct RenderSettings {
  int width = 512;
  int height = 512;
  int subframes = 1;  // jittered colour samples averaged per frame
  // Tone mapping: display = 1 - exp(-radiance * exposureScale), then sRGB.
  // With 0.002 a white Lambert surface lit head-on by a distant light of
  // intensity 4000 maps to about 0.92 (sRGB 246); lamps of 20,000-120,000
  // at a few metres give moderate to bright pools of light.
  float exposureScale = 0.002f;
  int shadowMapSize = 2048;
};

class Renderer {
 public:
  Renderer(GlContext& context, const AssetResolver& assets, const RenderSettings& settings);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders camera `cameraIndex` of `list` into `out` (resized as needed).
  // Asset problems (missing or corrupt mesh or texture) throw RunError
  // naming the prim and the file.
  void render(const RenderList& list, size_t cameraIndex, FramePasses& out);
  const RenderSettings& settings() const { return settings_; }

 private:
  struct GpuMesh;
  struct Uniforms;
  const GpuMesh& mesh(const RenderItem& item);
  unsigned texture(const std::string& path, const std::string& primPath);
  void drawShadowMap(const RenderList& list, int lightIndex, Matrix4d& lightViewProjection);
  void drawScene(const RenderList& list, const RenderCamera& camera, const Eigen::Vector2d& jitter,
                 const Matrix4d& lightViewProjection, int shadowLight);
  void readBack(FramePasses& out, bool colorOnly);

  GlContext& context_;
  const GlApi& gl_;
  const AssetResolver& assets_;
  RenderSettings settings_;
  unsigned sceneProgram_ = 0, shadowProgram_ = 0;
  std::unique_ptr<Uniforms> uniforms_;
  unsigned framebuffer_ = 0, shadowFramebuffer_ = 0;
  unsigned colorTexture_ = 0, normalTexture_ = 0, planeTexture_ = 0, idTexture_ = 0, depthTexture_ = 0;
  unsigned shadowTexture_ = 0, whiteTexture_ = 0;
  std::unordered_map<std::string, std::unique_ptr<GpuMesh>> meshes_;
  std::unordered_map<std::string, unsigned> textures_;
  std::vector<uint32_t> colorSum_;
  std::vector<uint8_t> scratchRgba_;
  std::vector<float> scratchFloat_;
};

// Resolves and loads mesh data for a key (shape generator or file).
MeshData meshDataFor(const MeshKey& key, const AssetResolver& assets, const std::string& primPath);

}  // namespace sdg
