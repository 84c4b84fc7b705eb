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
    gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, r.maskBuffer);
    gl_.glReadPixels(0, 0, w, h, GL_RED_INTEGER, GL_UNSIGNED_INT, reinterpret_cast<void*>(layer * layerBytes));
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
  gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, r.maskBuffer);
  const void* pixels = gl_.glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, GLsizeiptr(words * sizeof(uint32_t)), GL_MAP_READ_BIT);
  if (!pixels) throw RunError("renderer: cannot map the coverage read-back buffer");
  std::copy_n(static_cast<const uint32_t*>(pixels), words, out.bits.data());
  gl_.glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
  gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

void Renderer::coverageOf(const CoverageMasks& masks, std::vector<Coverage>& out) { coverageOfMasks(masks, out); }

}  // namespace sdg
