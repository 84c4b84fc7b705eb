#pragma once
// Images read through OpenImageIO: PNG, JPEG, TIFF, OpenEXR, Radiance HDR,
// TGA, BMP and WebP, from files or from memory (textures embedded in glTF
// and FBX files), decoded to what the renderers upload.
//
// Colour handling (docs/rendering.md, "Textures and colour"):
// - integer files (8 and 16 bits per channel) hold sRGB-encoded colour when
//   used as colour (base colour, domes) and plain values when used as data
//   (roughness, metallic, normal maps, opacity);
// - floating-point files (EXR, HDR, float TIFF) hold linear values;
// - alpha is always linear; grey files are replicated into R, G and B;
//   files without alpha get alpha 1.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace sdg {

// Documented limits for images read from disk or memory, checked on the
// header before any pixel is decoded.
inline constexpr uint32_t kMaxTextureSide = 16384;
inline constexpr uint64_t kMaxTexturePixels = 64ull << 20;  // 64 Mpixel

struct ImageRgba8 {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> pixels;  // rows top to bottom, 4 bytes per pixel
};

// Linear RGBA floats, rows top to bottom, 4 floats per pixel.
struct ImageRgbaF {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> pixels;
};

// What the pixels of a texture mean, which decides how 8-bit output is
// encoded.
enum class TextureData {
  Color,   // 8-bit output is sRGB-encoded (float sources are encoded to sRGB)
  Linear,  // 8-bit output is the value itself times 255 (float sources clamped)
};

struct ImageHeader {
  uint32_t width = 0;
  uint32_t height = 0;
  int channels = 0;
  int bitsPerChannel = 8;
  bool floatingPoint = false;  // EXR, HDR, float TIFF: linear radiance or data
  std::string format;          // OpenImageIO's format name: "png", "jpeg", "openexr", ...
};

// Every function throws RunError whose message starts with the file (or
// `name` for images in memory) and says what is wrong: missing, not an
// image of a readable format, over the limits, corrupt or truncated.

// The header only: cheap, used by `validate`.
ImageHeader readImageHeader(const std::string& path);

ImageRgba8 loadImageRgba8(const std::string& path, TextureData data);
ImageRgbaF loadImageLinear(const std::string& path);

// The same for an encoded image held in memory (a PNG or JPEG inside a glTF
// file, say); `name` stands for the file in messages, and its extension,
// if any, is a hint to the format.
ImageRgba8 decodeImageRgba8(const void* bytes, size_t size, const std::string& name, TextureData data);
ImageRgbaF decodeImageLinear(const void* bytes, size_t size, const std::string& name);

// The sRGB transfer curve and its inverse on [0, 1].
float srgbToLinear(float encoded);
float linearToSrgb(float linear);

}  // namespace sdg
