// Images through OpenImageIO: every format sdgbehave reads decodes to the
// known pattern tools/make_images.cpp wrote (tests/data/images/formats/),
// colour is sRGB-decoded or encoded by file kind and TextureData, memory
// decodes as the file does, and every damaged file (tests/data/images/
// corrupt/) is a RunError naming it, with nothing printed by the libraries.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "assets/image.h"
#include "core/diagnostics.h"
#include "render/latlong.h"

using namespace sdg;

namespace {

const std::string kFormats = SDG_SOURCE_DIR "/tests/data/images/formats/";
const std::string kCorrupt = SDG_SOURCE_DIR "/tests/data/images/corrupt/";
constexpr int kW = 8, kH = 4;

// The pattern's 8-bit codes, as tools/make_images.cpp writes them.
std::array<uint8_t, 4> patternCode(int x, int y) {
  return {uint8_t(16 + 28 * x), uint8_t(20 + 60 * y), uint8_t(200 - 12 * x - 30 * y), uint8_t(255 - 8 * x - 16 * y)};
}

// Its 16-bit samples: code * 257 +- 100, which round back to the code.
uint16_t pattern16(uint8_t c) { return uint16_t(c * 257 + (c < 128 ? 100 : -100)); }

uint8_t patternGrey(int x, int y) { return uint8_t(10 + 28 * x + 7 * y); }

std::vector<char> fileBytes(const std::string& path) {
  std::vector<char> bytes(std::filesystem::file_size(path));
  std::ifstream(path, std::ios::binary).read(bytes.data(), std::streamsize(bytes.size()));
  return bytes;
}

// Every pixel of an 8 x 4 RGBA8 image against the pattern, within
// `tolerance` codes; `alpha` false: the file has none, so 255.
void checkPattern(const ImageRgba8& image, int tolerance, bool alpha) {
  REQUIRE((image.width == kW && image.height == kH));
  REQUIRE(image.pixels.size() == size_t(kW * kH * 4));
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const auto want = patternCode(x, y);
      const uint8_t* got = &image.pixels[size_t(y * kW + x) * 4];
      CAPTURE(x, y);
      for (int c = 0; c < 3; ++c) CHECK(std::abs(int(got[c]) - int(want[size_t(c)])) <= tolerance);
      CHECK(int(got[3]) == (alpha ? want[3] : 255));
    }
}

const float* pixelF(const ImageRgbaF& image, int x, int y) {
  return &image.pixels[(size_t(y) * image.width + size_t(x)) * 4];
}

// Captures what is written to file descriptor 2 (libraries print with
// fprintf(stderr), below any C++ stream) while it lives.
class StderrCapture {
 public:
  StderrCapture() : file_(std::tmpfile()), saved_(dup(2)) {
    std::fflush(stderr);
    dup2(fileno(file_), 2);
  }
  ~StderrCapture() {
    restore();
    std::fclose(file_);
  }
  std::string text() {
    restore();
    std::string out;
    std::rewind(file_);
    for (int c; (c = std::fgetc(file_)) != EOF;) out += char(c);
    return out;
  }

 private:
  void restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    dup2(saved_, 2);
    close(saved_);
    saved_ = -1;
  }
  std::FILE* file_;
  int saved_;
};

}  // namespace

TEST_CASE("image formats: lossless 8- and 16-bit files decode to the pattern exactly", "[assets][images]") {
  for (const char* name : {"pattern.png", "pattern8.tif", "pattern.tga", "pattern16.png", "pattern16.tif"}) {
    CAPTURE(name);
    checkPattern(loadImageRgba8(kFormats + name, TextureData::Color), 0, true);
    // Integer files hold codes: Linear gives the same bytes.
    checkPattern(loadImageRgba8(kFormats + name, TextureData::Linear), 0, true);
  }
  checkPattern(loadImageRgba8(kFormats + "pattern.bmp", TextureData::Color), 0, false);
}

TEST_CASE("image formats: headers say size, channels, depth and kind", "[assets][images]") {
  struct Expected {
    const char* file;
    int channels, bits;
    bool floating;
    const char* format;
  };
  for (const Expected& e : {Expected{"pattern.png", 4, 8, false, "png"}, Expected{"pattern16.png", 4, 16, false, "png"},
                            Expected{"pattern.jpg", 3, 8, false, "jpeg"},
                            Expected{"pattern16.tif", 4, 16, false, "tiff"},
                            Expected{"pattern_float.tif", 4, 32, true, "tiff"},
                            Expected{"pattern_half.exr", 4, 16, true, "openexr"},
                            Expected{"pattern.hdr", 3, 32, true, "hdr"}, Expected{"pattern.tga", 4, 8, false, "targa"},
                            Expected{"grey_alpha.png", 2, 8, false, "png"}}) {
    CAPTURE(e.file);
    const ImageHeader h = readImageHeader(kFormats + e.file);
    CHECK((h.width == uint32_t(kW) && h.height == uint32_t(kH)));
    CHECK(h.channels == e.channels);
    CHECK(h.bitsPerChannel == e.bits);
    CHECK(h.floatingPoint == e.floating);
    CHECK(h.format == e.format);
  }
}

TEST_CASE("image formats: JPEG (quality 100) within 3 codes, without alpha", "[assets][images]") {
  checkPattern(loadImageRgba8(kFormats + "pattern.jpg", TextureData::Color), 3, false);
}

TEST_CASE("image formats: WebP colour and straight alpha", "[assets][images]") {
  // The pattern 4 times larger (make_images.cpp says why): the middle of
  // each 4 x 4 block holds its colour.
  const ImageRgba8 big = loadImageRgba8(kFormats + "pattern.webp", TextureData::Color);
  REQUIRE((big.width == 32 && big.height == 16));
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      CAPTURE(x, y);
      const uint8_t* got = &big.pixels[size_t((4 * y + 2) * 32 + 4 * x + 2) * 4];
      for (int c = 0; c < 3; ++c) CHECK(std::abs(int(got[c]) - int(patternCode(x, y)[size_t(c)])) <= 2);
      CHECK(got[3] == 255);
    }
  // Straight (200, 100, 50) at alpha 128 in the file; premultiplied it
  // would read as about (100, 50, 25).
  const ImageRgba8 alpha = loadImageRgba8(kFormats + "alpha.webp", TextureData::Color);
  const int want[4] = {200, 100, 50, 128};
  for (int c = 0; c < 4; ++c) CHECK(std::abs(int(alpha.pixels[size_t(c)]) - want[c]) <= 3);
}

TEST_CASE("image formats: grey and grey + alpha are replicated into R, G and B", "[assets][images]") {
  const ImageRgba8 grey = loadImageRgba8(kFormats + "grey.png", TextureData::Linear);
  const ImageRgba8 greyAlpha = loadImageRgba8(kFormats + "grey_alpha.png", TextureData::Linear);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      CAPTURE(x, y);
      const size_t p = size_t(y * kW + x) * 4;
      const uint8_t g = patternGrey(x, y);
      CHECK((grey.pixels[p] == g && grey.pixels[p + 1] == g && grey.pixels[p + 2] == g && grey.pixels[p + 3] == 255));
      CHECK((greyAlpha.pixels[p] == g && greyAlpha.pixels[p + 2] == g));
      CHECK(greyAlpha.pixels[p + 3] == patternCode(x, y)[3]);
    }
}

TEST_CASE("image formats: linear loads sRGB-decode integer colour, never alpha", "[assets][images]") {
  const ImageRgbaF png = loadImageLinear(kFormats + "pattern.png");
  const ImageRgbaF png16 = loadImageLinear(kFormats + "pattern16.png");
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      CAPTURE(x, y);
      const auto code = patternCode(x, y);
      for (int c = 0; c < 3; ++c) {
        CHECK(pixelF(png, x, y)[c] == srgbToLinear(code[size_t(c)] / 255.0f));
        CHECK(pixelF(png16, x, y)[c] == srgbToLinear(pattern16(code[size_t(c)]) / 65535.0f));
      }
      CHECK(pixelF(png, x, y)[3] == code[3] / 255.0f);
      CHECK(pixelF(png16, x, y)[3] == pattern16(code[3]) / 65535.0f);
    }
  // The pattern's red 128 (x = 4) as colour.
  CHECK(pixelF(png, 4, 0)[0] == srgbToLinear(128 / 255.0f));
  const ImageRgbaF grey = loadImageLinear(kFormats + "grey.png");
  CHECK(pixelF(grey, 3, 2)[1] == srgbToLinear(patternGrey(3, 2) / 255.0f));
  CHECK(pixelF(grey, 3, 2)[3] == 1.0f);
}

TEST_CASE("image formats: float files are linear, as stored", "[assets][images]") {
  for (const char* name : {"pattern_float.exr", "pattern_float.tif", "pattern_half.exr"}) {
    CAPTURE(name);
    const bool half = std::string(name).find("half") != std::string::npos;
    const ImageRgbaF image = loadImageLinear(kFormats + name);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        CAPTURE(x, y);
        const auto code = patternCode(x, y);
        for (int c = 0; c < 4; ++c) {
          const float want = c == 3 ? code[3] / 255.0f : srgbToLinear(code[size_t(c)] / 255.0f);
          CHECK(pixelF(image, x, y)[c] == Approx(want).epsilon(half ? 1e-3 : 0).margin(half ? 1e-6 : 0));
        }
      }
    // Colour encoded back to sRGB gives the codes: exact for float, within
    // one code for half.
    checkPattern(loadImageRgba8(kFormats + name, TextureData::Color), half ? 1 : 0, true);
  }
  // Radiance HDR: RGBE keeps 8 bits of mantissa under the brightest
  // channel's exponent.
  const ImageRgbaF hdr = loadImageLinear(kFormats + "pattern.hdr");
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      CAPTURE(x, y);
      const auto code = patternCode(x, y);
      float brightest = 0;
      for (int c = 0; c < 3; ++c) brightest = std::max(brightest, srgbToLinear(code[size_t(c)] / 255.0f));
      for (int c = 0; c < 3; ++c)
        CHECK(pixelF(hdr, x, y)[c] == Approx(srgbToLinear(code[size_t(c)] / 255.0f)).margin(brightest / 128));
      CHECK(pixelF(hdr, x, y)[3] == 1.0f);
    }
}

TEST_CASE("image formats: float to 8 bits: Color encodes to sRGB, Linear scales, both clamp", "[assets][images]") {
  // probe.exr (float) and probe_half.exr: (0.5, 0.5, 0.5, 0.5), then (4, -1, 0.25, 1).
  const auto encoded = [](float v) { return uint8_t(std::lround(255 * linearToSrgb(v))); };
  CHECK(encoded(0.5f) == 188);
  for (const char* name : {"probe.exr", "probe_half.exr"}) {
    CAPTURE(name);
    const ImageRgba8 colour = loadImageRgba8(kFormats + name, TextureData::Color);
    const ImageRgba8 linear = loadImageRgba8(kFormats + name, TextureData::Linear);
    CHECK(colour.pixels == std::vector<uint8_t>{encoded(0.5f), encoded(0.5f), encoded(0.5f), 128,  //
                                                255, 0, encoded(0.25f), 255});
    CHECK(linear.pixels == std::vector<uint8_t>{128, 128, 128, 128, 255, 0, 64, 255});
    // Loaded as floats, nothing is clamped.
    const ImageRgbaF floats = loadImageLinear(kFormats + name);
    CHECK(floats.pixels == std::vector<float>{0.5f, 0.5f, 0.5f, 0.5f, 4.0f, -1.0f, 0.25f, 1.0f});
  }
}

TEST_CASE("image formats: memory decodes as the file does, the name's extension is only a hint", "[assets][images]") {
  for (const char* name : {"pattern.png", "pattern.jpg", "pattern16.tif", "pattern_half.exr", "pattern.webp"}) {
    CAPTURE(name);
    const std::vector<char> bytes = fileBytes(kFormats + name);
    // No extension: the format is read from the first bytes.
    for (const std::string& label : {std::string(name), std::string("embedded texture 0")}) {
      CHECK(decodeImageRgba8(bytes.data(), bytes.size(), label, TextureData::Color).pixels ==
            loadImageRgba8(kFormats + name, TextureData::Color).pixels);
      CHECK(decodeImageLinear(bytes.data(), bytes.size(), label).pixels == loadImageLinear(kFormats + name).pixels);
    }
  }
  // TGA has no signature: its name must say what it is.
  const std::vector<char> tga = fileBytes(kFormats + "pattern.tga");
  checkPattern(decodeImageRgba8(tga.data(), tga.size(), "image.tga", TextureData::Color), 0, true);
  CHECK_THROWS_WITH(decodeImageRgba8(tga.data(), tga.size(), "image", TextureData::Color),
                    Catch::StartsWith("image: not an image sdgbehave can read"));
}

TEST_CASE("image formats: damaged files are RunErrors that name the file, and nothing is printed", "[assets][images]") {
  struct Case {
    const char* file;
    const char* says;
  };
  StderrCapture stderrText;
  for (const Case& c : {Case{"truncated.png", "the PNG is truncated"}, Case{"truncated.jpg", "the JPEG is truncated"},
                        Case{"truncated.exr", "the OpenEXR is corrupt or truncated"},
                        Case{"text.exr", "not a readable OpenEXR image"}, Case{"empty.hdr", "the file is empty"},
                        Case{"huge_header.png", "declares 20000 x 20000 pixels"}}) {
    const std::string path = kCorrupt + c.file;
    CAPTURE(path);
    CHECK_THROWS_WITH(loadImageRgba8(path, TextureData::Color),
                      Catch::StartsWith(path + ": ") && Catch::Contains(c.says));
    CHECK_THROWS_WITH(loadImageLinear(path), Catch::StartsWith(path + ": ") && Catch::Contains(c.says));
    const std::vector<char> bytes = fileBytes(path);
    CHECK_THROWS_WITH(decodeImageLinear(bytes.data(), bytes.size(), c.file),
                      Catch::StartsWith(std::string(c.file) + ": "));
  }
  // Headers alone: the truncated files' headers are whole; the others are not.
  for (const char* intact : {"truncated.png", "truncated.jpg", "truncated.exr"})
    CHECK_NOTHROW(readImageHeader(kCorrupt + intact));
  for (const char* broken : {"text.exr", "empty.hdr", "huge_header.png"})
    CHECK_THROWS_AS(readImageHeader(kCorrupt + broken), RunError);
  CHECK_THROWS_WITH(loadImageRgba8(kCorrupt + "missing.png", TextureData::Color),
                    Catch::Equals(kCorrupt + "missing.png: not found"));
  CHECK(stderrText.text().empty());
}

TEST_CASE("image formats: the limits are checked on the header, before any pixel", "[assets][images]") {
  // huge_header.png holds one byte of pixel data: decoding would fail
  // otherwise, so the size message shows the header was refused first.
  const std::string path = kCorrupt + "huge_header.png";
  for (auto load : {+[](const std::string& p) { readImageHeader(p); },
                    +[](const std::string& p) { loadImageRgba8(p, TextureData::Color); },
                    +[](const std::string& p) { loadImageLinear(p); }})
    CHECK_THROWS_WITH(load(path), Catch::Contains("declares 20000 x 20000 pixels; images are limited to 16384 a side"));
  const std::vector<char> bytes = fileBytes(path);
  CHECK_THROWS_WITH(decodeImageRgba8(bytes.data(), bytes.size(), "huge", TextureData::Color),
                    Catch::Contains("declares 20000 x 20000 pixels"));
}

TEST_CASE("image formats: the sRGB curve and its inverse", "[assets][images]") {
  CHECK(srgbToLinear(0.0f) == 0.0f);
  CHECK(srgbToLinear(1.0f) == Approx(1.0f));
  CHECK(srgbToLinear(0.04045f) == Approx(0.04045f / 12.92f));
  CHECK(srgbToLinear(0.5f) == Approx(0.2140411f));
  for (int code = 0; code <= 255; ++code)
    CHECK(std::lround(255 * linearToSrgb(srgbToLinear(code / 255.0f))) == code);
}

TEST_CASE("skies: the sunset sky has its sun where it says, thousands of times the sky", "[assets][images]") {
  for (const char* name : {"sunset_sky.exr", "sunset_sky.hdr"}) {
    CAPTURE(name);
    const std::string path = std::string(SDG_SOURCE_DIR "/scenes/skies/") + name;
    const ImageRgbaF sky = loadImageLinear(path);
    REQUIRE((sky.width == 512 && sky.height == 256));
    // Elevation 10 degrees, azimuth 45 degrees from +Z towards +X, +Y up.
    const float el = 10 * kLatLongPi / 180, az = 45 * kLatLongPi / 180;
    const Eigen::Vector2f uv =
        latLongFromDirection({std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)});
    const float sun = pixelF(sky, int(uv.x() * 512), int(uv.y() * 256))[1];
    const float zenith = pixelF(sky, 256, 0)[1], horizon = pixelF(sky, 0, 127)[1];
    CHECK(sun > 2000 * horizon);
    CHECK(horizon > zenith);  // a sunset: the sky is brightest low down
  }
  const ImageRgbaF overcast = loadImageLinear(SDG_SOURCE_DIR "/scenes/skies/overcast_sky.exr");
  float brightest = 0;
  for (float v : overcast.pixels) brightest = std::max(brightest, v);
  CHECK(brightest <= 1.0f);  // no sun
}

TEST_CASE("textures: the project's textures read with the channels they need", "[assets][images]") {
  const std::string dir = SDG_SOURCE_DIR "/scenes/textures/";
  CHECK(readImageHeader(dir + "concrete.jpg").channels == 3);
  for (const char* grey : {"concrete_roughness.png", "plate_metallic.png", "grate_opacity.png"}) {
    CAPTURE(grey);
    CHECK(readImageHeader(dir + grey).channels == 1);
  }
  // A tangent-space normal map: every texel a unit vector facing out.
  const ImageRgba8 n = loadImageRgba8(dir + "concrete_normal.png", TextureData::Linear);
  for (size_t p = 0; p < n.pixels.size(); p += 4) {
    const float x = n.pixels[p] / 127.5f - 1, y = n.pixels[p + 1] / 127.5f - 1, z = n.pixels[p + 2] / 127.5f - 1;
    REQUIRE(std::abs(std::sqrt(x * x + y * y + z * z) - 1) < 0.02f);
    REQUIRE(z > 0);
  }
}
