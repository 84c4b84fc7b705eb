// Coverage masks: each entity drawn as if alone, for unoccluded extents
// (loose boxes, occlusion).
#include "render/raster/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "core/diagnostics.h"
#include "render/camera_math.h"
#include "render/raster/renderer_internal.h"
#include "render/raster/gl_textures.h"
#include "render/raster/shaders.h"

namespace sdg {

using namespace raster_detail;

void Renderer::queueCoverage(const RenderList& list, size_t cameraIndex, const std::vector<std::vector<size_t>>& groups,
                             int slot) {
  ReadSlot& r = readSlots_[slot & 1];
  const int w = settings_.width, h = settings_.height;
  r.maskGroups = groups.size();
  r.masksPending = true;
  if (groups.empty()) return;
  if (maskWidth_ != w || maskHeight_ != h) {
    unsigned old[] = {maskTexture_, maskDepth_};
    gl_.glDeleteTextures(2, old);
    maskTexture_ = makeTexture(gl_, GL_R32UI, w, h, GL_RED_INTEGER, GL_UNSIGNED_INT);
    maskDepth_ = makeTexture(gl_, GL_DEPTH_COMPONENT24, w, h, GL_DEPTH_COMPONENT, GL_FLOAT);
    gl_.glBindFramebuffer(GL_FRAMEBUFFER, maskFramebuffer_);
    gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, maskTexture_, 0);
    gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, maskDepth_, 0);
    const GLenum buffer = GL_COLOR_ATTACHMENT0;
    gl_.glDrawBuffers(1, &buffer);
    maskWidth_ = w;
    maskHeight_ = h;
  }
  const size_t layers = (groups.size() + 31) / 32;
  const size_t layerBytes = size_t(w) * size_t(h) * sizeof(uint32_t);
  if (!r.maskBuffer) gl_.glGenBuffers(1, &r.maskBuffer);
  gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, r.maskBuffer);
  if (r.maskBufferBytes < layers * layerBytes) {
    r.maskBufferBytes = layers * layerBytes;
    gl_.glBufferData(GL_PIXEL_PACK_BUFFER, GLsizeiptr(r.maskBufferBytes), nullptr, GL_STREAM_READ);
  }
  const RenderCamera& camera = list.cameras[cameraIndex];
  if (!camera.lens.calibrated()) {
    drawMaskLayers(list, camera, groups, r.maskBuffer, nullptr);
    return;
  }
  // A calibrated lens: each of its views' masks read back here, then every
  // pixel of the lens's image takes its view pixel's bits (render/lens_views.h).
  LensViewPlan& plan = lensPlans_[camera.path];
  if (!lensPlanFits(plan, camera, w, h)) plan = planLensViews(camera, w, h);
  const size_t layerWords = size_t(w) * size_t(h);
  r.lensMasks.assign(layers * layerWords, 0u);
  lensMaskView_.resize(layers * layerWords);
  for (size_t v = 0; v < plan.viewTemplates.size(); ++v) {
    drawMaskLayers(list, lensView(plan, camera, v), groups, 0, lensMaskView_.data());
    for (size_t i = 0; i < layerWords; ++i) {
      if (plan.view[i] != int32_t(v)) continue;
      // Mask rows are bottom first, the plan's top first.
      const size_t x = i % size_t(w), y = i / size_t(w);
      const size_t sx = plan.sourcePixel[i] % size_t(w), sy = plan.sourcePixel[i] / size_t(w);
      const size_t to = (size_t(h) - 1 - y) * size_t(w) + x, from = (size_t(h) - 1 - sy) * size_t(w) + sx;
      for (size_t layer = 0; layer < layers; ++layer)
        r.lensMasks[layer * layerWords + to] = lensMaskView_[layer * layerWords + from];
    }
  }
  r.lensMasksReady = true;
}

// Every layer of 32 groups drawn from `camera` and read back into the pixel
// buffer `buffer` (layer after layer), or, with `cpu`, into that memory.
void Renderer::drawMaskLayers(const RenderList& list, const RenderCamera& camera,
                              const std::vector<std::vector<size_t>>& groups, unsigned buffer, uint32_t* cpu) {
  const int w = settings_.width, h = settings_.height;
  const size_t layers = (groups.size() + 31) / 32;
  const size_t layerBytes = size_t(w) * size_t(h) * sizeof(uint32_t);
  const Matrix4d viewProjection = projectionMatrix(camera, w, h) * viewMatrix(camera);
  gl_.glBindFramebuffer(GL_FRAMEBUFFER, maskFramebuffer_);
  gl_.glViewport(0, 0, w, h);
  // Each entity writes its own bit with OR and no depth test, so one pass
  // (and one read-back) covers 32 entities drawn as if alone.
  gl_.glDisable(GL_DEPTH_TEST);
  gl_.glEnable(GL_COLOR_LOGIC_OP);
  gl_.glLogicOp(GL_OR);
  gl_.glUseProgram(maskProgram_);
  resolveMeshes(list);
  setMatrix(gl_, maskViewProjection_, viewProjection);
  gl_.glPixelStorei(GL_PACK_ALIGNMENT, 1);
  gl_.glReadBuffer(GL_COLOR_ATTACHMENT0);
  const unsigned zero[4] = {0, 0, 0, 0};
  for (size_t layer = 0; layer < layers; ++layer) {
    const size_t first = layer * 32, last = std::min(groups.size(), first + 32);
    gl_.glClearBufferuiv(GL_COLOR, 0, zero);
    maskBatches_.buildMasks(list, meshSlots_, groups, first, last);
    uploadInstances(maskBatches_, maskInstanceBuffer_);
    drawWholeMeshes(maskBatches_, maskInstanceBuffer_);
    gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, cpu ? 0 : buffer);
    void* at = cpu ? static_cast<void*>(reinterpret_cast<uint8_t*>(cpu) + layer * layerBytes)
                   : reinterpret_cast<void*>(layer * layerBytes);
    gl_.glReadPixels(0, 0, w, h, GL_RED_INTEGER, GL_UNSIGNED_INT, at);
  }
  gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  gl_.glDisable(GL_COLOR_LOGIC_OP);
  gl_.glEnable(GL_DEPTH_TEST);
  gl_.glBindVertexArray(0);
}

void Renderer::collectCoverage(int slot, CoverageMasks& out) {
  ReadSlot& r = readSlots_[slot & 1];
  if (!r.masksPending) throw RunError("renderer: no coverage was queued in read-back slot " + std::to_string(slot));
  r.masksPending = false;
  out.width = settings_.width;
  out.height = settings_.height;
  out.groups = r.maskGroups;
  const size_t words = (r.maskGroups + 31) / 32 * size_t(out.width) * size_t(out.height);
  out.bits.resize(words);
  if (!words) return;
  if (r.lensMasksReady) {  // already resampled on the CPU
    r.lensMasksReady = false;
    std::copy_n(r.lensMasks.data(), words, out.bits.data());
    return;
  }
  gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, r.maskBuffer);
  const void* pixels = gl_.glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, GLsizeiptr(words * sizeof(uint32_t)), GL_MAP_READ_BIT);
  if (!pixels) throw RunError("renderer: cannot map the coverage read-back buffer");
  std::copy_n(static_cast<const uint32_t*>(pixels), words, out.bits.data());
  gl_.glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
  gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

void Renderer::coverageOf(const CoverageMasks& masks, std::vector<Coverage>& out) { coverageOfMasks(masks, out); }

}  // namespace sdg
