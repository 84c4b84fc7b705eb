// The rasterizer's textures: material maps (files and images embedded in
// mesh files) and the pre-filtered textures of dome maps.
#include "render/raster/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "core/diagnostics.h"
#include "render/camera_math.h"
#include "render/raster/renderer_internal.h"
#include "render/raster/shaders.h"
#include "assets/texture_source.h"
#include "render/raster/environment_map.h"
#include "render/raster/gl_textures.h"

namespace sdg {

using namespace raster_detail;

namespace {

// The dome as the camera sees it is halved (2 x 2 box averages) until at
// most four texels per output pixel span the horizon (2048 at least): more
// is more than any camera shows, and uploading a 4096-wide map's 8 million
// texels as half floats costs llvmpipe a quarter second.
ImageRgbaF halved(const ImageRgbaF& in) {
  ImageRgbaF half{in.width / 2, in.height / 2, std::vector<float>(size_t(in.width / 2) * (in.height / 2) * 4)};
  for (uint32_t y = 0; y < half.height; ++y) {
    const float* top = in.pixels.data() + size_t(2 * y) * in.width * 4;
    const float* bottom = top + size_t(in.width) * 4;
    float* out = half.pixels.data() + size_t(y) * half.width * 4;
    for (uint32_t x = 0; x < half.width; ++x)
      for (size_t c = 0; c < 4; ++c)
        out[4 * x + c] = 0.25f * (top[8 * x + c] + top[8 * x + 4 + c] + bottom[8 * x + c] + bottom[8 * x + 4 + c]);
  }
  return half;
}

// Whether the dome is wider than the camera needs and can be halved.
bool halvable(const ImageRgbaF& map, int maxWidth) {
  return int(map.width) > maxWidth && map.width % 2 == 0 && map.height % 2 == 0;
}

}  // namespace

ImageRgba8 Renderer::decodeTexture(const std::string& key, const std::string& primPath, TextureData data) const {
  auto embedded = embeddedImages_.find(key);
  return decodeTextureImage(key, embedded == embeddedImages_.end() ? nullptr : &embedded->second, assets_, data,
                            primPath);
}

const Renderer::GpuTexture& Renderer::texture(const std::string& key, const std::string& primPath, TextureData data) {
  auto& cache = data == TextureData::Color ? colorTextures_ : dataTextures_;
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  const ImageRgba8 image = decodeTexture(key, primPath, data);
  const unsigned t = data == TextureData::Color ? makeSrgbTexture(gl_, image) : makeDataTexture(gl_, image);
  return cache.emplace(key, GpuTexture{t}).first->second;
}

void Renderer::bindMaps(const MaterialMaps& maps, const std::string& primPath) {
  auto bind = [&](int unit, const std::string& key, TextureData data) {
    gl_.glActiveTexture(GLenum(GL_TEXTURE0 + unit));
    gl_.glBindTexture(GL_TEXTURE_2D, key.empty() ? whiteTexture_ : texture(key, primPath, data).id);
  };
  bind(kBaseUnit, maps.baseColor, TextureData::Color);
  if (!maps.roughness.empty()) bind(kRoughnessUnit, maps.roughness, TextureData::Linear);
  if (!maps.metallic.empty()) bind(kMetallicUnit, maps.metallic, TextureData::Linear);
  if (!maps.orm.empty()) bind(kOrmUnit, maps.orm, TextureData::Linear);
  if (!maps.normal.empty()) bind(kNormalUnit, maps.normal, TextureData::Linear);
  if (!maps.opacity.empty()) bind(kOpacityUnit, maps.opacity, TextureData::Linear);
  gl_.glActiveTexture(GL_TEXTURE0);
}

const Renderer::DomeTextures& Renderer::dome(const RenderLight& light) {
  auto it = domes_.find(light.texture);
  if (it != domes_.end()) return it->second;
  const ImageRgbaF map = loadDomeMap(light.texture, assets_, light.path);
  if (domes_.size() >= kMaxCachedDomes) {
    auto oldest = domes_.begin();  // any: which one goes is not visible in the output
    unsigned ids[] = {oldest->second.background, oldest->second.specular, oldest->second.irradiance};
    gl_.glDeleteTextures(3, ids);
    domes_.erase(oldest);
  }
  const PrefilteredEnvironment prefiltered = prefilterEnvironment(map);
  DomeTextures d;
  const int backgroundWidth = std::max(2048, 4 * settings_.width);
  if (halvable(map, backgroundWidth)) {
    ImageRgbaF background = halved(map);
    while (halvable(background, backgroundWidth)) background = halved(background);
    d.background = makeLatLongTexture(gl_, background);
  } else {
    d.background = makeLatLongTexture(gl_, map);
  }
  std::vector<const LatLong*> levels;
  for (const LatLong& level : prefiltered.specular) levels.push_back(&level);
  d.specular = makeLatLongTexture(gl_, levels);
  d.specularLevels = int(levels.size());
  d.irradiance = makeLatLongTexture(gl_, std::vector<const LatLong*>{&prefiltered.irradiance});
  return domes_.emplace(light.texture, d).first->second;
}

}  // namespace sdg
