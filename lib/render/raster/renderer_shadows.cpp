// The rasterizer's shadow maps: which lights get one, what each covers and
// which flat items they may leave out.
#include "render/raster/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "core/diagnostics.h"
#include "render/camera_math.h"
#include "render/raster/gl_textures.h"
#include "render/raster/renderer_internal.h"
#include "render/raster/shaders.h"
#include "render/raster/shadow_casters.h"
#include "render/raster/shadow_frusta.h"

namespace sdg {

using namespace raster_detail;

int Renderer::shadowMapSize() const {
  if (settings_.shadowMapSize > 0) return settings_.shadowMapSize;
  return std::clamp(std::max(settings_.width, settings_.height), 256, 4096);
}

Eigen::AlignedBox3d Renderer::sceneBounds(const RenderList& list) {
  itemBounds_.resize(list.items.size());
  Eigen::AlignedBox3d box;
  for (size_t i = 0; i < list.items.size(); ++i) {
    const RenderItem& item = list.items[i];
    const Eigen::AlignedBox3f& b = meshBySlot_[meshSlots_[i]]->bounds;
    Eigen::AlignedBox3d& world = itemBounds_[i];
    world.setEmpty();
    if (!b.isEmpty())
      for (int c = 0; c < 8; ++c) {
        Vec3d corner = b.corner(static_cast<Eigen::AlignedBox3f::CornerType>(c)).cast<double>();
        world.extend((item.worldFromLocal * corner.homogeneous()).head<3>());
      }
    box.extend(world);
  }
  if (box.isEmpty()) box.extend(Vec3d::Zero());
  return box;
}

void Renderer::markShadowlessBatches(const RenderLight& light, const Eigen::AlignedBox3d& scene) {
  // Each flat instance tested costs a pass over every item's bounds, so a
  // frame tests a few (ground planes, backdrops) and draws the rest.
  constexpr int kMaxFlatInstancesTested = 8;
  const double tolerance = 1e-6 * std::max(1.0, scene.diagonal().norm());
  const std::vector<InstanceBatch>& byMesh = batches_.byMesh();
  const std::vector<InstanceRecord>& records = batches_.records();
  skipInShadow_.assign(byMesh.size(), 0);
  int budget = kMaxFlatInstancesTested;
  for (size_t b = 0; b < byMesh.size(); ++b) {
    const InstanceBatch& batch = byMesh[b];
    const Eigen::AlignedBox3f& local = meshBySlot_[batch.meshSlot]->bounds;
    if (int(batch.count) > budget || !flatAxis(local)) continue;
    bool skip = true;
    for (uint32_t k = 0; k < batch.count && skip; ++k) {
      --budget;
      const std::optional<FlatSurface> surface = flatSurface(local, records[batch.first + k].worldFromLocal);
      skip = surface && shadowsNothing(*surface, light, itemBounds_, tolerance);
    }
    skipInShadow_[b] = skip ? 1 : 0;
  }
}

void Renderer::drawShadowMaps(const RenderList& list, const RenderCamera& camera) {
  const Eigen::AlignedBox3d scene = sceneBounds(list);
  const Eigen::AlignedBox3d receivers = visibleRegion(camera, settings_.width, settings_.height, scene);
  for (ShadowSlot& slot : shadowSlots_)
    slot.viewProjection = shadowViewProjection(list.lights[slot.light], receivers, scene);
  const int size = shadowMapSize();
  if (!shadowAtlas_) {
    shadowAtlas_ = makeTexture(gl_, GL_DEPTH_COMPONENT24, 2 * size, 2 * size, GL_DEPTH_COMPONENT, GL_FLOAT);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl_.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl_.glBindFramebuffer(GL_FRAMEBUFFER, shadowFramebuffer_);
    gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, shadowAtlas_, 0);
  }
  // One framebuffer, one clear, a viewport per light: llvmpipe flushes on
  // every framebuffer switch, so tiles of one atlas cost far less than maps.
  // The clear covers the whole atlas, unused tiles too: llvmpipe clears a
  // whole framebuffer by filling its tiles, but a scissored clear by drawing
  // a quad through the depth pipeline (1.2 ms a frame for three tiles).
  gl_.glBindFramebuffer(GL_FRAMEBUFFER, shadowFramebuffer_);
  const float one = 1.0f;
  gl_.glClearBufferfv(GL_DEPTH, 0, &one);
  gl_.glEnable(GL_SCISSOR_TEST);  // each light draws only into its tile
  gl_.glEnable(GL_DEPTH_TEST);
  gl_.glDepthFunc(GL_LESS);
  gl_.glEnable(GL_POLYGON_OFFSET_FILL);
  gl_.glPolygonOffset(2.0f, 4.0f);
  gl_.glUseProgram(shadowProgram_);
  for (size_t k = 0; k < shadowSlots_.size(); ++k) {
    gl_.glViewport(GLint(k % 2) * size, GLint(k / 2) * size, size, size);
    gl_.glScissor(GLint(k % 2) * size, GLint(k / 2) * size, size, size);
    setMatrix(gl_, shadowLightViewProjection_, shadowSlots_[k].viewProjection);
    markShadowlessBatches(list.lights[shadowSlots_[k].light], scene);
    drawWholeMeshes(batches_, instanceBuffer_, &skipInShadow_);
  }
  gl_.glDisable(GL_POLYGON_OFFSET_FILL);
  gl_.glDisable(GL_SCISSOR_TEST);
}

}  // namespace sdg
