#include "render/pathtrace/pt_textures.h"

#include <array>
#include <cmath>
#include <optional>

#include "assets/texture_source.h"
#include "core/diagnostics.h"

namespace sdg {
namespace {

// 8-bit sRGB code -> linear, the decode GL applies to sRGB textures.
const std::array<float, 256>& srgbTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (size_t k = 0; k < t.size(); ++k) t[k] = srgbToLinear(float(k) / 255.0f);
    return t;
  }();
  return table;
}

// GL_REPEAT: an index taken modulo the size, negative ones included.
uint32_t wrap(int64_t i, uint32_t size) {
  const int64_t m = i % int64_t(size);
  return uint32_t(m < 0 ? m + size : m);
}

}  // namespace

PtTexture::PtTexture(ImageRgba8 image, TextureData data)
    : image_(std::move(image)), srgb_(data == TextureData::Color) {}

Eigen::Vector4f PtTexture::texel(uint32_t x, uint32_t y) const {
  const uint8_t* p = &image_.pixels[(size_t(y) * image_.width + x) * 4];
  if (srgb_) {
    const auto& t = srgbTable();
    return {t[p[0]], t[p[1]], t[p[2]], float(p[3]) * (1.0f / 255.0f)};  // alpha stays linear
  }
  return Eigen::Vector4f(p[0], p[1], p[2], p[3]) * (1.0f / 255.0f);
}

Eigen::Vector4f PtTexture::sample(const Vec2f& uv) const {
  if (!std::isfinite(uv.x()) || !std::isfinite(uv.y())) return texel(0, 0);
  // Into [0, 1) first (GL_REPEAT), so far-away coordinates keep their
  // fraction and the texel index stays small; then the texel centres sit
  // at half-integers: the four around the point, blended.
  const float x = (uv.x() - std::floor(uv.x())) * float(image_.width) - 0.5f;
  const float y = (uv.y() - std::floor(uv.y())) * float(image_.height) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  const float ax = x - fx, ay = y - fy;
  const int64_t ix = int64_t(fx), iy = int64_t(fy);
  const uint32_t x0 = wrap(ix, image_.width), x1 = wrap(ix + 1, image_.width);
  const uint32_t y0 = wrap(iy, image_.height), y1 = wrap(iy + 1, image_.height);
  return (texel(x0, y0) * (1.0f - ax) + texel(x1, y0) * ax) * (1.0f - ay) +
         (texel(x0, y1) * (1.0f - ax) + texel(x1, y1) * ax) * ay;
}

void PtTextureCache::addEmbedded(const std::vector<EmbeddedImage>& images) {
  for (const EmbeddedImage& image : images) embedded_.try_emplace(image.key, image);
}

ImageRgba8 PtTextureCache::decode(const std::string& key, TextureData data, const std::string& primPath) const {
  auto embedded = embedded_.find(key);
  return decodeTextureImage(key, embedded == embedded_.end() ? nullptr : &embedded->second, assets_, data, primPath);
}

const PtTexture* PtTextureCache::get(const std::string& key, TextureData data, const std::string& primPath) {
  if (key.empty()) return nullptr;
  auto it = textures_.find({key, data});
  if (it != textures_.end()) return it->second.get();
  ImageRgba8 image = decode(key, data, primPath);
  if (image.width == 0 || image.height == 0 || image.pixels.size() < size_t(image.width) * image.height * 4)
    throw RunError(primPath + ": texture '" + key + "' has no pixels");
  auto texture = std::make_unique<PtTexture>(std::move(image), data);
  return textures_.emplace(std::make_pair(key, data), std::move(texture)).first->second.get();
}

}  // namespace sdg
