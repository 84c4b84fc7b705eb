#include "writers/png_encoder.h"

#include <png.h>
#include <zlib.h>

#include <stdexcept>

namespace sdg {
namespace {
void appendBytes(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::vector<uint8_t>*>(png_get_io_ptr(png));
  out->insert(out->end(), data, data + length);
}
void noFlush(png_structp) {}
[[noreturn]] void onError(png_structp, png_const_charp message) { throw std::runtime_error(message); }
void onWarning(png_structp, png_const_charp) {}
}  // namespace

std::vector<uint8_t> encodePng(std::span<const uint8_t> pixels, uint32_t width, uint32_t height, PngPixels format,
                               const PngOptions& options) {
  std::vector<uint8_t> out;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, onError, onWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    throw std::runtime_error("libpng: out of memory");
  }
  try {
    png_set_write_fn(png, &out, appendBytes, noFlush);
    int colorType = format == PngPixels::Rgba8  ? PNG_COLOR_TYPE_RGBA
                    : format == PngPixels::Rgb8 ? PNG_COLOR_TYPE_RGB
                                                : PNG_COLOR_TYPE_GRAY;
    int bitDepth = format == PngPixels::Gray16 ? 16 : 8;
    size_t bytesPerPixel = format == PngPixels::Rgba8    ? 4
                           : format == PngPixels::Rgb8   ? 3
                           : format == PngPixels::Gray16 ? 2
                                                         : 1;
    png_set_IHDR(png, info, width, height, bitDepth, colorType, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    png_set_compression_level(png, options.zlibLevel);
    png_set_compression_strategy(png, options.runLengthOnly ? Z_RLE : Z_DEFAULT_STRATEGY);
    png_set_filter(png, PNG_FILTER_TYPE_BASE,
                   options.filter == PngFilter::None  ? PNG_FILTER_NONE
                   : options.filter == PngFilter::Sub ? PNG_FILTER_SUB
                                                      : PNG_FILTER_UP);
    png_write_info(png, info);
    if (bitDepth == 16) png_set_swap(png);  // PNG is big-endian; our samples are little-endian
    const size_t stride = width * bytesPerPixel;
    for (uint32_t y = 0; y < height; ++y)
      png_write_row(png, const_cast<png_bytep>(pixels.data() + y * stride));
    png_write_end(png, nullptr);
  } catch (...) {
    png_destroy_write_struct(&png, &info);
    throw;
  }
  png_destroy_write_struct(&png, &info);
  return out;
}

}  // namespace sdg
