#include "assets/image.h"

#include <png.h>

#include <cstring>

#include "core/diagnostics.h"

namespace sdg {

ImageRgba8 loadPng(const std::string& path) {
  png_image image;
  std::memset(&image, 0, sizeof image);
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str()))
    throw RunError(path + ": cannot read the PNG: " + image.message);
  if (image.width > kMaxTextureSide || image.height > kMaxTextureSide ||
      uint64_t(image.width) * image.height > kMaxTexturePixels) {
    uint32_t w = image.width, h = image.height;
    png_image_free(&image);
    throw RunError(path + ": the PNG declares " + std::to_string(w) + " x " + std::to_string(h) +
                   " pixels; textures are limited to " + std::to_string(kMaxTextureSide) + " a side and " +
                   std::to_string(kMaxTexturePixels >> 20) + " Mpixel");
  }
  image.format = PNG_FORMAT_RGBA;
  ImageRgba8 out;
  out.width = image.width;
  out.height = image.height;
  out.pixels.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.pixels.data(), 0, nullptr)) {
    std::string message = image.message;
    png_image_free(&image);
    throw RunError(path + ": corrupt PNG: " + message);
  }
  return out;
}

}  // namespace sdg
