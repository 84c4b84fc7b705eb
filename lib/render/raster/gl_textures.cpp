#include "render/raster/gl_textures.h"

#include <algorithm>

#include "assets/mipmaps.h"

namespace sdg {
namespace {

unsigned makeMipmapped(const GlApi& gl, GLint internalFormat, const ImageRgba8& image,
                       const std::vector<ImageRgba8>& levels) {
  unsigned t = 0;
  gl.glGenTextures(1, &t);
  gl.glBindTexture(GL_TEXTURE_2D, t);
  gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.glTexImage2D(GL_TEXTURE_2D, 0, internalFormat, GLsizei(image.width), GLsizei(image.height), 0, GL_RGBA,
                  GL_UNSIGNED_BYTE, image.pixels.data());
  for (size_t i = 0; i < levels.size(); ++i)
    gl.glTexImage2D(GL_TEXTURE_2D, GLint(i + 1), internalFormat, GLsizei(levels[i].width), GLsizei(levels[i].height),
                    0, GL_RGBA, GL_UNSIGNED_BYTE, levels[i].pixels.data());
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return t;
}

// Half floats hold at most 65504; brighter texels (a sun) would become
// infinite and poison every filter tap that touches them.
constexpr float kHalfMax = 65504.0f;

void uploadLevel(const GlApi& gl, int level, int w, int h, GLenum format, const float* data,
                 std::vector<float>& scratch, size_t count) {
  scratch.resize(count);
  std::transform(data, data + count, scratch.begin(), [](float v) { return std::min(v, kHalfMax); });
  gl.glTexImage2D(GL_TEXTURE_2D, level, GL_RGB16F, w, h, 0, format, GL_FLOAT, scratch.data());
}

void latLongSampling(const GlApi& gl, int levels) {
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, levels - 1);
}

}  // namespace

unsigned makeSrgbTexture(const GlApi& gl, const ImageRgba8& image) {
  return makeMipmapped(gl, GL_SRGB8_ALPHA8, image, srgbMipLevels(image));
}

unsigned makeDataTexture(const GlApi& gl, const ImageRgba8& image) {
  return makeMipmapped(gl, GL_RGBA8, image, linearMipLevels(image));
}

unsigned makeTexture(const GlApi& gl, GLint internalFormat, int w, int h, GLenum format, GLenum type) {
  unsigned t = 0;
  gl.glGenTextures(1, &t);
  gl.glBindTexture(GL_TEXTURE_2D, t);
  gl.glTexImage2D(GL_TEXTURE_2D, 0, internalFormat, w, h, 0, format, type, nullptr);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

unsigned makeLatLongTexture(const GlApi& gl, const std::vector<const LatLong*>& levels) {
  unsigned t = 0;
  gl.glGenTextures(1, &t);
  gl.glBindTexture(GL_TEXTURE_2D, t);
  gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  std::vector<float> scratch;
  for (size_t i = 0; i < levels.size(); ++i) {
    const LatLong& l = *levels[i];
    uploadLevel(gl, int(i), l.width, l.height, GL_RGB, l.rgb.data(), scratch, l.rgb.size());
  }
  latLongSampling(gl, int(levels.size()));
  return t;
}

unsigned makeLatLongTexture(const GlApi& gl, const ImageRgbaF& image) {
  unsigned t = 0;
  gl.glGenTextures(1, &t);
  gl.glBindTexture(GL_TEXTURE_2D, t);
  gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  std::vector<float> scratch;
  uploadLevel(gl, 0, int(image.width), int(image.height), GL_RGBA, image.pixels.data(), scratch, image.pixels.size());
  latLongSampling(gl, 1);
  return t;
}

unsigned makeLutTexture(const GlApi& gl, const SplitSumLut& lut) {
  unsigned t = 0;
  gl.glGenTextures(1, &t);
  gl.glBindTexture(GL_TEXTURE_2D, t);
  gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_RG32F, lut.size, lut.size, 0, GL_RG, GL_FLOAT, lut.scaleBias.data());
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return t;
}

}  // namespace sdg
