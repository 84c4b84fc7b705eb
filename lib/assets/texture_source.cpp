#include "assets/texture_source.h"

#include "assets/packaged_image.h"
#include "core/diagnostics.h"

namespace sdg {
namespace {

std::string resolveOrThrow(const std::string& file, const AssetResolver& assets) {
  std::optional<std::string> resolved = assets.resolve(file);
  if (!resolved) throw RunError("texture '" + file + "' not found; " + assets.describeSearch(file));
  return *resolved;
}

ImageRgba8 decodeEmbedded(const EmbeddedImage& e, TextureData data) {
  const std::vector<uint8_t>& bytes = *e.bytes;
  if (e.rawWidth == 0) return decodeImageRgba8(bytes.data(), bytes.size(), e.name, data);
  // assimp's raw texels are b, g, r, a.
  ImageRgba8 image{e.rawWidth, e.rawHeight, std::vector<uint8_t>(bytes.size())};
  for (size_t i = 0; i + 3 < bytes.size(); i += 4) {
    image.pixels[i] = bytes[i + 2];
    image.pixels[i + 1] = bytes[i + 1];
    image.pixels[i + 2] = bytes[i];
    image.pixels[i + 3] = bytes[i + 3];
  }
  return image;
}

}  // namespace

ImageRgba8 decodeTextureImage(const std::string& key, const EmbeddedImage* embedded, const AssetResolver& assets,
                              TextureData data, const std::string& owner) {
  try {
    if (embedded) return decodeEmbedded(*embedded, data);
    if (isPackagedAssetPath(key)) {  // a texture of a .usdz stage
      std::vector<uint8_t> bytes = readPackagedAsset(key, assets);
      return decodeImageRgba8(bytes.data(), bytes.size(), key, data);
    }
    return loadImageRgba8(resolveOrThrow(key, assets), data);
  } catch (const RunError& e) {
    throw RunError(owner + ": " + e.what());
  }
}

ImageRgbaF loadDomeMap(const std::string& file, const AssetResolver& assets, const std::string& owner) {
  try {
    return loadImageLinear(resolveOrThrow(file, assets));
  } catch (const RunError& e) {
    throw RunError(owner + ": " + e.what());
  }
}

}  // namespace sdg
