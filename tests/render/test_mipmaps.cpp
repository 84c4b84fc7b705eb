// The CPU mip chain of sRGB textures: GL's level sizes, linear-light
// averaging with rounding to the nearest sRGB code, area weights on odd sides.
#include <catch2/catch.hpp>

#include "assets/mipmaps.h"

using namespace sdg;

namespace {
ImageRgba8 image(uint32_t w, uint32_t h, std::vector<uint8_t> rgba) { return ImageRgba8{w, h, std::move(rgba)}; }

ImageRgba8 grey(uint32_t w, uint32_t h, const std::vector<uint8_t>& codes) {
  std::vector<uint8_t> rgba;
  for (uint8_t c : codes) rgba.insert(rgba.end(), {c, c, c, 255});
  return image(w, h, rgba);
}
}  // namespace

TEST_CASE("mipmaps: levels halve each side, rounding down, to 1 x 1", "[render][mipmaps]") {
  const auto levels = srgbMipLevels(image(5, 3, std::vector<uint8_t>(5 * 3 * 4, 7)));
  REQUIRE(levels.size() == 2);
  CHECK((levels[0].width == 2 && levels[0].height == 1));
  CHECK((levels[1].width == 1 && levels[1].height == 1));
  CHECK(srgbMipLevels(image(64, 64, std::vector<uint8_t>(64 * 64 * 4, 0))).size() == 6);
  CHECK(srgbMipLevels(image(1, 1, {1, 2, 3, 4})).empty());
  const auto tall = srgbMipLevels(image(1, 4, std::vector<uint8_t>(16, 9)));
  REQUIRE(tall.size() == 2);
  CHECK((tall[0].width == 1 && tall[0].height == 2 && tall[1].height == 1));
}

TEST_CASE("mipmaps: a uniform texture keeps every code exactly", "[render][mipmaps]") {
  for (int code = 0; code < 256; ++code) {
    const uint8_t c = uint8_t(code);
    const auto levels = srgbMipLevels(image(2, 2, {c, c, c, c, c, c, c, c, c, c, c, c, c, c, c, c}));
    REQUIRE(levels.size() == 1);
    CHECK(levels[0].pixels == std::vector<uint8_t>{c, c, c, c});
  }
}

TEST_CASE("mipmaps: colour averages in linear light, alpha as stored", "[render][mipmaps]") {
  // Black and white: half the light is sRGB 187.5 -> 188 (not the 128 of
  // averaging codes); alpha 0 and 255 average to 127.5 -> 128.
  auto level = srgbMipLevels(image(2, 2, {0, 0, 0, 0, 255, 255, 255, 255, 0, 0, 0, 0, 255, 255, 255, 255}))[0];
  CHECK(level.pixels == std::vector<uint8_t>{188, 188, 188, 128});
  // 200 and 100 -> 160.2 -> 160; 10 and 250 -> 184.03 -> 184.
  CHECK(srgbMipLevels(grey(2, 1, {200, 100}))[0].pixels[0] == 160);
  CHECK(srgbMipLevels(grey(1, 2, {10, 250}))[0].pixels[0] == 184);
}

TEST_CASE("mipmaps: an odd side weighs each covered texel by its area", "[render][mipmaps]") {
  // 3 -> 1: each source texel covers a third: a third of the light is sRGB
  // 156.19 -> 156, wherever the white texel is.
  for (int white = 0; white < 3; ++white) {
    std::vector<uint8_t> codes(3, 0);
    codes[size_t(white)] = 255;
    CHECK(srgbMipLevels(grey(3, 1, codes))[0].pixels[0] == 156);
  }
  // 5 -> 2: the middle texel is shared, half to each side.
  const auto level = srgbMipLevels(grey(5, 1, {0, 0, 255, 0, 0}))[0];
  CHECK(level.pixels[0] == level.pixels[4]);
  CHECK(level.pixels[0] > 0);
}
