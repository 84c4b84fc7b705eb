// The rasterizer's render targets and their read-back: synchronous, or
// queued into pixel buffer objects and collected a frame later.
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

namespace sdg {

using namespace raster_detail;

namespace {

// Bytes per pixel of each attachment as it is read back.
constexpr size_t kAttachmentBytes[4] = {4, 16, 4, 4};

void readAttachment(const GlApi& gl, int attachment, int w, int h, void* target) {
  gl.glReadBuffer(GLenum(GL_COLOR_ATTACHMENT0 + attachment));
  switch (attachment) {
    case 0: gl.glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, target); break;
    case 1: gl.glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, target); break;
    case 2: gl.glReadPixels(0, 0, w, h, GL_RED, GL_FLOAT, target); break;
    default: gl.glReadPixels(0, 0, w, h, GL_RED_INTEGER, GL_UNSIGNED_INT, target); break;
  }
}


}  // namespace

void Renderer::unpack(int attachment, const void* pixels, FramePasses& out) {
  const int w = settings_.width, h = settings_.height;
  const size_t n = size_t(w) * size_t(h);
  // GL rows run bottom to top; outputs run top to bottom.
  auto flipInto = [&](const auto* source, auto* target, size_t perPixel) {
    const size_t row = size_t(w) * perPixel;
    for (int y = 0; y < h; ++y) std::copy_n(source + size_t(h - 1 - y) * row, row, target + size_t(y) * row);
  };
  switch (attachment) {
    case 0: flipInto(static_cast<const uint8_t*>(pixels), out.rgba.data(), 4); break;
    case 1:
      flipInto(static_cast<const float*>(pixels), out.normals.data(), 4);
      for (size_t i = 0; i < n; ++i) {
        out.distanceToCamera[i] = out.normals[4 * i + 3];
        out.normals[4 * i + 3] = 0.0f;
      }
      break;
    case 2: flipInto(static_cast<const float*>(pixels), out.distanceToImagePlane.data(), 1); break;
    default: flipInto(static_cast<const uint32_t*>(pixels), out.instanceIds.data(), 1); break;
  }
}

void Renderer::readBack(FramePasses& out, bool colorOnly, const PassSelection& passes) {
  const int w = settings_.width, h = settings_.height;
  const size_t n = size_t(w) * size_t(h);
  gl_.glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.glPixelStorei(GL_PACK_ALIGNMENT, 1);
  scratchRgba_.resize(n * 4);
  readAttachment(gl_, 0, w, h, scratchRgba_.data());
  if (colorOnly) {
    for (int y = 0; y < h; ++y)
      for (size_t i = 0; i < size_t(w) * 4; ++i) colorSum_[size_t(y) * w * 4 + i] += scratchRgba_[size_t(h - 1 - y) * w * 4 + i];
    return;
  }
  unpack(0, scratchRgba_.data(), out);
  scratchFloat_.resize(n * 4);
  for (int attachment = 1; attachment < 4; ++attachment) {
    if (!wanted(attachment, passes)) continue;
    readAttachment(gl_, attachment, w, h, scratchFloat_.data());
    unpack(attachment, scratchFloat_.data(), out);
  }
}

void Renderer::ensureTargets() {
  const int w = settings_.width, h = settings_.height;
  if (colorTexture_) return;
  colorTexture_ = makeTexture(gl_, GL_RGBA8, w, h, GL_RGBA, GL_UNSIGNED_BYTE);
  normalTexture_ = makeTexture(gl_, GL_RGBA32F, w, h, GL_RGBA, GL_FLOAT);
  planeTexture_ = makeTexture(gl_, GL_R32F, w, h, GL_RED, GL_FLOAT);
  idTexture_ = makeTexture(gl_, GL_R32UI, w, h, GL_RED_INTEGER, GL_UNSIGNED_INT);
  depthTexture_ = makeTexture(gl_, GL_DEPTH_COMPONENT24, w, h, GL_DEPTH_COMPONENT, GL_FLOAT);
  gl_.glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colorTexture_, 0);
  gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, normalTexture_, 0);
  gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, GL_TEXTURE_2D, planeTexture_, 0);
  gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT3, GL_TEXTURE_2D, idTexture_, 0);
  gl_.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depthTexture_, 0);
  const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
  gl_.glDrawBuffers(4, buffers);
  if (gl_.glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw RunError("renderer: the framebuffer for " + std::to_string(w) + " x " + std::to_string(h) +
                   " is incomplete (out of memory?)");
}

void Renderer::queue(const RenderList& list, size_t cameraIndex, const PassSelection& passes, int slot) {
  ReadSlot& r = readSlots_[slot & 1];
  const bool lens = cameraIndex < list.cameras.size() && list.cameras[cameraIndex].lens.calibrated();
  if (settings_.subframes > 1 || lens) {
    render(list, cameraIndex, r.frame, passes);
    r.synchronous = true;
    r.pending = true;
    return;
  }
  drawFrame(list, cameraIndex, passes);
  const int w = settings_.width, h = settings_.height;
  gl_.glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.glPixelStorei(GL_PACK_ALIGNMENT, 1);
  for (int attachment = 0; attachment < 4; ++attachment) {
    if (!wanted(attachment, passes)) continue;
    if (!r.buffers[attachment]) {
      gl_.glGenBuffers(1, &r.buffers[attachment]);
      gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, r.buffers[attachment]);
      gl_.glBufferData(GL_PIXEL_PACK_BUFFER, GLsizeiptr(size_t(w) * size_t(h) * kAttachmentBytes[attachment]), nullptr,
                       GL_STREAM_READ);
    }
    gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, r.buffers[attachment]);
    readAttachment(gl_, attachment, w, h, nullptr);  // into the bound buffer: returns at once
  }
  gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  r.passes = passes;
  r.synchronous = false;
  r.pending = true;
}

void Renderer::collect(int slot, FramePasses& out) {
  ReadSlot& r = readSlots_[slot & 1];
  if (!r.pending) throw RunError("renderer: nothing was queued in read-back slot " + std::to_string(slot));
  r.pending = false;
  if (r.synchronous) {
    std::swap(out, r.frame);
    return;
  }
  const int w = settings_.width, h = settings_.height;
  out.resize(w, h, r.passes);
  for (int attachment = 0; attachment < 4; ++attachment) {
    if (!wanted(attachment, r.passes)) continue;
    const size_t bytes = size_t(w) * size_t(h) * kAttachmentBytes[attachment];
    gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, r.buffers[attachment]);
    const void* pixels = gl_.glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, GLsizeiptr(bytes), GL_MAP_READ_BIT);
    if (!pixels) throw RunError("renderer: cannot map the read-back buffer of attachment " + std::to_string(attachment));
    unpack(attachment, pixels, out);
    gl_.glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
  }
  gl_.glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

}  // namespace sdg
