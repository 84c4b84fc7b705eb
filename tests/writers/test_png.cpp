// PNG encoding: each pixel format reads back (through the image reader,
// which expands to RGBA8) with the values written.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "assets/image.h"
#include "writers/png_encoder.h"
#include "scratch_name.h"

using namespace sdg;

namespace {
ImageRgba8 roundTrip(const std::vector<uint8_t>& png) {
  const auto path = sdg::test::uniqueTempPath("sdg_png_roundtrip").concat(".png");
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
  ImageRgba8 image = loadImageRgba8(path.string(), TextureData::Color);
  std::filesystem::remove(path);
  return image;
}
}  // namespace

TEST_CASE("png: RGBA, RGB and grey pixels read back as written", "[writers][png]") {
  // 3 x 2 pixels with distinct values in every channel.
  std::vector<uint8_t> rgba, rgb, grey;
  for (uint8_t p = 0; p < 6; ++p) {
    rgba.insert(rgba.end(), {uint8_t(10 * p), uint8_t(10 * p + 1), uint8_t(10 * p + 2), uint8_t(200 + p)});
    rgb.insert(rgb.end(), {uint8_t(40 * p), uint8_t(40 * p + 3), uint8_t(40 * p + 7)});
    grey.push_back(uint8_t(50 * p));
  }
  ImageRgba8 a = roundTrip(encodePng(rgba, 3, 2, PngPixels::Rgba8));
  CHECK((a.width == 3 && a.height == 2));
  CHECK(a.pixels == rgba);
  ImageRgba8 b = roundTrip(encodePng(rgb, 3, 2, PngPixels::Rgb8));
  for (size_t p = 0; p < 6; ++p) {
    CAPTURE(p);
    CHECK(std::vector<uint8_t>(b.pixels.begin() + ptrdiff_t(4 * p), b.pixels.begin() + ptrdiff_t(4 * p + 3)) ==
          std::vector<uint8_t>(rgb.begin() + ptrdiff_t(3 * p), rgb.begin() + ptrdiff_t(3 * p + 3)));
    CHECK(b.pixels[4 * p + 3] == 255);  // opaque
  }
  ImageRgba8 c = roundTrip(encodePng(grey, 3, 2, PngPixels::Gray8));
  for (size_t p = 0; p < 6; ++p) CHECK(c.pixels[4 * p] == grey[p]);
}

TEST_CASE("png: every preset keeps every pixel and reaches libpng", "[writers][png]") {
  // A shaded 64 x 64 frame: smooth gradients with a hard-edged square.
  const uint32_t w = 64, h = 64;
  std::vector<uint8_t> frame;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const bool square = x >= 20 && x < 40 && y >= 24 && y < 44;
      frame.insert(frame.end(), {uint8_t(square ? 200 : 2 * x + y), uint8_t(square ? 30 : 3 * y), uint8_t(x ^ y), 255});
    }
  const std::vector<uint8_t> plain = encodePng(frame, w, h, PngPixels::Rgba8);
  for (const PngOptions& options : {PngOptions::renderedImage(), PngOptions::labelMap(), PngOptions::drawing()}) {
    CAPTURE(int(options.filter), options.runLengthOnly);
    const std::vector<uint8_t> png = encodePng(frame, w, h, PngPixels::Rgba8, options);
    CHECK(png != plain);  // the filter or the matching reached libpng and zlib
    CHECK(roundTrip(png).pixels == frame);
    CHECK(png.size() < frame.size());  // compressed, not stored
  }
}
