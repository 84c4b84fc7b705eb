#pragma once
// Material textures for the path tracer: decoded once, kept as 8-bit RGBA
// (as the rasterizer uploads them), sampled bilinearly with wrap-around.
//
// Sampling follows GL's texture() on the rasterizer's textures exactly
// where it can: texel centres at (i + 0.5) / size, rows top first with the
// row at t = v (images are uploaded top row first), GL_REPEAT in both
// directions, and for colour maps the sRGB decode applied to each texel
// before the blend (as GL does for an sRGB texture). What differs: no mip
// maps (the path tracer's jittered pixel samples average the footprint
// instead).
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "assets/asset_resolver.h"
#include "assets/image.h"
#include "assets/mesh_data.h"
#include "stage/math_types.h"

namespace sdg {

class PtTexture {
 public:
  PtTexture(ImageRgba8 image, TextureData data);

  // Linear RGBA at texture coordinate `uv` (u right, v down the image).
  Eigen::Vector4f sample(const Vec2f& uv) const;
  uint32_t width() const { return image_.width; }
  uint32_t height() const { return image_.height; }
  const ImageRgba8& image() const { return image_; }
  bool srgb() const { return srgb_; }  // a colour map: texels are decoded from sRGB

 private:
  Eigen::Vector4f texel(uint32_t x, uint32_t y) const;

  ImageRgba8 image_;
  bool srgb_;
};

// Textures by key and meaning (a file used both as colour and as data is
// two textures, as on the GPU). Not thread-safe: get() loads, so every
// texture a frame needs is fetched before the frame's threads start; after
// that the textures are only read.
class PtTextureCache {
 public:
  explicit PtTextureCache(const AssetResolver& assets) : assets_(assets) {}

  // Images embedded in a mesh file, found by their "embedded:" keys.
  void addEmbedded(const std::vector<EmbeddedImage>& images);
  // The texture of `key` ("" gives nullptr); a missing or unreadable file
  // is a RunError that names `primPath`, as the rasterizer words it.
  const PtTexture* get(const std::string& key, TextureData data, const std::string& primPath);

 private:
  ImageRgba8 decode(const std::string& key, TextureData data, const std::string& primPath) const;

  const AssetResolver& assets_;
  std::map<std::string, EmbeddedImage> embedded_;
  std::map<std::pair<std::string, TextureData>, std::unique_ptr<PtTexture>> textures_;
};

}  // namespace sdg
