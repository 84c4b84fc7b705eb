// Generates the images this project makes (see
// third_party_notes/project-assets.md), all procedural and deterministic,
// written through OpenImageIO:
// - tests/data/images/formats/: one 8 x 4 pattern in every format sdgbehave
//   reads, and a float probe (test_image_formats.cpp checks the pixels);
// - tests/data/images/corrupt/: truncated, empty, mislabelled and
//   over-limit files;
// - scenes/skies/: a sunset sky with a sun (EXR and Radiance HDR) and an
//   overcast sky, lat-long in the convention of lib/render/latlong.h;
// - scenes/textures/: a concrete base colour (JPEG), its roughness and
//   normal maps, a metallic map and an opacity map;
// - tests/data/isaac/pack/...: two small JPEGs under the names of Isaac
//   Sim's default textureRandomizer patterns.
//
//   build/release/tools/sdg_make_images <repository root>
//   (or: cmake --build build/release --target make_images)
#include <OpenImageIO/imageio.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "assets/image.h"
#include "render/latlong.h"

namespace {

namespace fs = std::filesystem;
using Eigen::Vector3f;

// ---------------------------------------------------------------- writing

template <typename T>
OIIO::TypeDesc typeOf() {
  if constexpr (std::is_same_v<T, uint8_t>) return OIIO::TypeUInt8;
  else if constexpr (std::is_same_v<T, uint16_t>) return OIIO::TypeUInt16;
  else return OIIO::TypeFloat;
}

// Writes `pixels` (rows top to bottom, interleaved channels) as `path`,
// stored as `storage`; `extra` adds format options to the spec.
template <typename T>
void save(const fs::path& path, int width, int height, int channels, const std::vector<T>& pixels,
          OIIO::TypeDesc storage, const std::function<void(OIIO::ImageSpec&)>& extra = {}) {
  OIIO::ImageSpec spec(width, height, channels, storage);
  // TIFF and OpenEXR stamp the time of writing unless given one: a fixed
  // stamp keeps reruns byte-identical.
  spec.attribute("DateTime", "2025:01:01 00:00:00");
  if (channels == 2 || channels == 4) {
    spec.alpha_channel = channels - 1;
    spec.attribute("oiio:UnassociatedAlpha", 1);  // straight alpha, written as given
  }
  if (extra) extra(spec);
  fs::create_directories(path.parent_path());
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out || !out->open(path.string(), spec) || !out->write_image(typeOf<T>(), pixels.data()) || !out->close())
    throw std::runtime_error(path.string() + ": " + (out ? out->geterror() : OIIO::geterror()));
  std::printf("%s\n", path.string().c_str());
}

void writeBytes(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
  std::printf("%s\n", path.string().c_str());
}

std::string readBytes(const fs::path& path) {
  std::string bytes(fs::file_size(path), '\0');
  std::ifstream(path, std::ios::binary).read(bytes.data(), std::streamsize(bytes.size()));
  return bytes;
}

// 8-bit codes from values in [0, 1], rounded.
uint8_t code(float v) { return uint8_t(std::lround(255.0f * std::clamp(v, 0.0f, 1.0f))); }

// ---------------------------------------------------------------- test pattern

constexpr int kPatternW = 8, kPatternH = 4;

// The pattern's 8-bit codes (tests/assets/test_image_formats.cpp has the
// same formula): every pixel a different colour, smooth enough for JPEG,
// alpha falling from 255 to 151.
std::array<uint8_t, 4> patternCode(int x, int y) {
  return {uint8_t(16 + 28 * x), uint8_t(20 + 60 * y), uint8_t(200 - 12 * x - 30 * y), uint8_t(255 - 8 * x - 16 * y)};
}

// 16-bit samples that are not multiples of 257, so that reading them as
// 8 bits must round: code * 257 +- 100 rounds back to the code.
uint16_t pattern16(uint8_t c) { return uint16_t(c * 257 + (c < 128 ? 100 : -100)); }

uint8_t patternGrey(int x, int y) { return uint8_t(10 + 28 * x + 7 * y); }

template <typename T>
std::vector<T> pattern(int channels, const std::function<T(uint8_t, bool alpha)>& sample) {
  std::vector<T> px;
  for (int y = 0; y < kPatternH; ++y)
    for (int x = 0; x < kPatternW; ++x) {
      const auto c = patternCode(x, y);
      for (int k = 0; k < channels; ++k) px.push_back(sample(c[size_t(k)], k == 3));
    }
  return px;
}

// OIIO 2.4's WebP writer converts to YUV 4:2:0 even for lossless output,
// and takes colour as premultiplied by alpha in linear light. So the
// pattern is written 4 times larger without alpha (each colour a 4 x 4
// block, whose middle survives the chroma subsampling), and alpha gets a
// one-colour file of its own, handed over premultiplied that way so that
// the file holds straight (200, 100, 50) at alpha 128.
void writeWebp(const fs::path& dir) {
  const int scale = 4, w = kPatternW * scale, h = kPatternH * scale;
  std::vector<uint8_t> rgb;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto c = patternCode(x / scale, y / scale);
      rgb.insert(rgb.end(), {c[0], c[1], c[2]});
    }
  const auto lossless = [](OIIO::ImageSpec& s) { s.attribute("compression", "lossless"); };
  save(dir / "pattern.webp", w, h, 3, rgb, OIIO::TypeUInt8, lossless);
  const float alpha = 128 / 255.0f;
  const auto premultiply = [&](float c) { return code(sdg::linearToSrgb(sdg::srgbToLinear(c / 255) * alpha)); };
  std::vector<uint8_t> premultiplied;
  for (int i = 0; i < 8 * 8; ++i)
    premultiplied.insert(premultiplied.end(), {premultiply(200), premultiply(100), premultiply(50), 128});
  save(dir / "alpha.webp", 8, 8, 4, premultiplied, OIIO::TypeUInt8, lossless);
}

void writeFormats(const fs::path& dir) {
  const auto bytes = [](uint8_t c, bool) { return c; };
  const auto words = [](uint8_t c, bool) { return pattern16(c); };
  // Float files hold linear light: colour is the sRGB code decoded, alpha the code / 255.
  const auto linear = [](uint8_t c, bool alpha) { return alpha ? c / 255.0f : sdg::srgbToLinear(c / 255.0f); };
  const auto rgba8 = pattern<uint8_t>(4, bytes), rgb8 = pattern<uint8_t>(3, bytes);
  const auto rgba16 = pattern<uint16_t>(4, words);
  const auto rgbaF = pattern<float>(4, linear), rgbF = pattern<float>(3, linear);
  const int w = kPatternW, h = kPatternH;

  save(dir / "pattern.png", w, h, 4, rgba8, OIIO::TypeUInt8);
  save(dir / "pattern16.png", w, h, 4, rgba16, OIIO::TypeUInt16);
  save(dir / "pattern.jpg", w, h, 3, rgb8, OIIO::TypeUInt8, [](OIIO::ImageSpec& s) {
    s.attribute("CompressionQuality", 100);
    s.attribute("jpeg:subsampling", "4:4:4");  // full-resolution colour: each pixel differs
  });
  save(dir / "pattern8.tif", w, h, 4, rgba8, OIIO::TypeUInt8);
  save(dir / "pattern16.tif", w, h, 4, rgba16, OIIO::TypeUInt16);
  save(dir / "pattern_float.tif", w, h, 4, rgbaF, OIIO::TypeFloat);
  const auto zip = [](OIIO::ImageSpec& s) { s.attribute("compression", "zip"); };
  save(dir / "pattern_half.exr", w, h, 4, rgbaF, OIIO::TypeHalf, zip);
  save(dir / "pattern_float.exr", w, h, 4, rgbaF, OIIO::TypeFloat, zip);
  save(dir / "pattern.hdr", w, h, 3, rgbF, OIIO::TypeFloat);
  save(dir / "pattern.tga", w, h, 4, rgba8, OIIO::TypeUInt8);
  save(dir / "pattern.bmp", w, h, 3, rgb8, OIIO::TypeUInt8);
  writeWebp(dir);

  std::vector<uint8_t> grey, greyAlpha;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      grey.push_back(patternGrey(x, y));
      greyAlpha.insert(greyAlpha.end(), {patternGrey(x, y), patternCode(x, y)[3]});
    }
  save(dir / "grey.png", w, h, 1, grey, OIIO::TypeUInt8);
  save(dir / "grey_alpha.png", w, h, 2, greyAlpha, OIIO::TypeUInt8);

  // Two pixels, float and half, whose 8-bit encodings the tests know: 0.5
  // everywhere, then values outside [0, 1] that must clamp (and stay as they
  // are in linear loads).
  const std::vector<float> probe = {0.5f, 0.5f, 0.5f, 0.5f, 4.0f, -1.0f, 0.25f, 1.0f};  // exact in half too
  save(dir / "probe.exr", 2, 1, 4, probe, OIIO::TypeFloat, zip);
  save(dir / "probe_half.exr", 2, 1, 4, probe, OIIO::TypeHalf, zip);
}

// ---------------------------------------------------------------- corrupt files

uint32_t crc32(const std::string& bytes) {
  uint32_t crc = 0xffffffffu;
  for (unsigned char b : bytes) {
    crc ^= b;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

std::string bigEndian(uint32_t v) {
  return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
}

std::string pngChunk(const std::string& kind, const std::string& data) {
  return bigEndian(uint32_t(data.size())) + kind + data + bigEndian(crc32(kind + data));
}

// A valid 64 x 64 image of noise, cut to the fraction `keep` of its bytes:
// the header survives, the pixel data stops early.
void writeTruncated(const fs::path& path, float keep) {
  const int side = 64;
  std::vector<uint8_t> px;
  for (int i = 0; i < side * side * 3; ++i) px.push_back(uint8_t((i * 2654435761u) >> 24));
  save(path, side, side, 3, px, OIIO::TypeUInt8, [](OIIO::ImageSpec& s) { s.attribute("compression", "zip"); });
  const std::string full = readBytes(path);
  writeBytes(path, full.substr(0, size_t(float(full.size()) * keep)));
}

void writeCorrupt(const fs::path& dir) {
  writeTruncated(dir / "truncated.png", 0.5f);
  writeTruncated(dir / "truncated.jpg", 0.5f);
  writeTruncated(dir / "truncated.exr", 0.6f);
  writeBytes(dir / "text.exr", "This is a text file with an .exr name, not an OpenEXR image.\n");
  writeBytes(dir / "empty.hdr", "");
  // A 20000 x 20000 RGB header followed by one row's worth of data: over
  // the limits, and refused before any pixel is decoded.
  const std::string ihdr = bigEndian(20000) + bigEndian(20000) + std::string{8, 2, 0, 0, 0};
  const std::string idat = {'\x78', '\x9c', '\x63', '\x00', '\x00', '\x00', '\x01', '\x00', '\x01'};  // zlib of one 0
  writeBytes(dir / "huge_header.png",
             "\x89PNG\r\n\x1a\n" + pngChunk("IHDR", ihdr) + pngChunk("IDAT", idat) + pngChunk("IEND", ""));
}

// ---------------------------------------------------------------- noise

uint32_t hash(uint32_t x, uint32_t y, uint32_t seed) {
  uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ seed * 0xcb1ab31fu;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  h ^= h >> 15;
  return h;
}

float lattice(int x, int y, int period, uint32_t seed) {
  const auto wrap = [period](int v) { return uint32_t(((v % period) + period) % period); };
  return float(hash(wrap(x), wrap(y), seed) >> 8) / float(1u << 24);
}

// Smooth value noise in [0, 1) that tiles every `period` lattice cells.
float valueNoise(float x, float y, int period, uint32_t seed) {
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const auto smooth = [](float t) { return t * t * (3 - 2 * t); };
  const float tx = smooth(x - float(x0)), ty = smooth(y - float(y0));
  const float a = lattice(x0, y0, period, seed), b = lattice(x0 + 1, y0, period, seed);
  const float c = lattice(x0, y0 + 1, period, seed), d = lattice(x0 + 1, y0 + 1, period, seed);
  return (a + (b - a) * tx) * (1 - ty) + (c + (d - c) * tx) * ty;
}

// Octaves of value noise over a texture of `size` pixels, tileable.
float fbm(int px, int py, int size, int basePeriod, int octaves, uint32_t seed) {
  float sum = 0, amplitude = 0.5f, norm = 0;
  int period = basePeriod;
  for (int o = 0; o < octaves; ++o, period *= 2, amplitude *= 0.5f) {
    const float scale = float(period) / float(size);
    sum += amplitude * valueNoise(float(px) * scale, float(py) * scale, period, seed + uint32_t(o));
    norm += amplitude;
  }
  return sum / norm;
}

// ---------------------------------------------------------------- textures

constexpr int kTex = 256;

void writeTextures(const fs::path& dir) {
  std::vector<uint8_t> colour, roughness, normal;
  std::vector<float> height(size_t(kTex * kTex));
  // Concrete: grey with cloudy variation and small dark pits.
  for (int y = 0; y < kTex; ++y)
    for (int x = 0; x < kTex; ++x) {
      const float cloud = fbm(x, y, kTex, 4, 5, 11);
      const float grain = fbm(x, y, kTex, 64, 2, 23);
      const float pit = grain < 0.18f ? 0.55f : 1.0f;
      const float v = (0.42f + 0.35f * cloud) * (0.9f + 0.2f * grain) * pit;
      colour.insert(colour.end(), {code(v * 1.02f), code(v), code(v * 0.95f)});
      roughness.push_back(code(0.72f + 0.22f * fbm(x, y, kTex, 8, 4, 31) + (pit < 1 ? 0.05f : 0.0f)));
    }
  save(dir / "concrete.jpg", kTex, kTex, 3, colour, OIIO::TypeUInt8,
       [](OIIO::ImageSpec& s) { s.attribute("CompressionQuality", 90); });
  save(dir / "concrete_roughness.png", kTex, kTex, 1, roughness, OIIO::TypeUInt8);

  // Tiles: 4 x 4 slabs whose edges bevel down into grooves, with a slight
  // bumpy surface; the tangent-space normal (OpenGL convention, +Y = green
  // up) is the height field's slope.
  const int tile = kTex / 4;
  for (int y = 0; y < kTex; ++y)
    for (int x = 0; x < kTex; ++x) {
      const int ex = std::min(x % tile, tile - 1 - x % tile), ey = std::min(y % tile, tile - 1 - y % tile);
      const float bevel = std::min(1.0f, float(std::min(ex, ey)) / 4.0f);
      height[size_t(y * kTex + x)] = 3.0f * bevel + 0.8f * fbm(x, y, kTex, 16, 3, 47);
    }
  const auto h = [&](int x, int y) { return height[size_t(((y + kTex) % kTex) * kTex + (x + kTex) % kTex)]; };
  for (int y = 0; y < kTex; ++y)
    for (int x = 0; x < kTex; ++x) {
      // Rows run top to bottom, so +Y (up the texture) is -row.
      const float dx = (h(x + 1, y) - h(x - 1, y)) / 2, dy = (h(x, y - 1) - h(x, y + 1)) / 2;
      const Vector3f n = Vector3f(-dx, -dy, 1.0f).normalized();
      normal.insert(normal.end(), {code(n.x() * 0.5f + 0.5f), code(n.y() * 0.5f + 0.5f), code(n.z() * 0.5f + 0.5f)});
    }
  save(dir / "concrete_normal.png", kTex, kTex, 3, normal, OIIO::TypeUInt8);

  // Metallic: bare metal (1) with painted diagonal stripes (0), edges
  // antialiased over 4 x 4 samples per pixel.
  const int side = 128, samples = 4;
  std::vector<uint8_t> metallic, opacity;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      float metal = 0, open = 0;
      for (int sy = 0; sy < samples; ++sy)
        for (int sx = 0; sx < samples; ++sx) {
          const float u = float(x) + (float(sx) + 0.5f) / samples, v = float(y) + (float(sy) + 0.5f) / samples;
          metal += std::fmod(u + v, 32.0f) < 16.0f ? 1.0f : 0.0f;
          // Grate: a 4 x 4 grid of round holes of radius 11 in 32-pixel cells.
          const float cx = std::fmod(u, 32.0f) - 16.0f, cy = std::fmod(v, 32.0f) - 16.0f;
          open += cx * cx + cy * cy < 11.0f * 11.0f ? 0.0f : 1.0f;
        }
      metallic.push_back(code(metal / (samples * samples)));
      opacity.push_back(code(open / (samples * samples)));
    }
  save(dir / "plate_metallic.png", side, side, 1, metallic, OIIO::TypeUInt8);
  save(dir / "grate_opacity.png", side, side, 1, opacity, OIIO::TypeUInt8);
}

// Small stand-ins for Isaac Sim's two default textureRandomizer patterns,
// so that the tests can point --isaac-assets at a pack that has them.
void writeIsaacPatterns(const fs::path& dir) {
  const int side = 32;
  std::vector<uint8_t> bamboo, brick;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const bool joint = x % 8 == 0;
      bamboo.insert(bamboo.end(), {uint8_t(joint ? 150 : 196), uint8_t(joint ? 130 : 170), uint8_t(joint ? 80 : 110)});
      const bool mortar = y % 8 == 0 || (x + (y / 8 % 2) * 8) % 16 == 0;
      const uint8_t grey = mortar ? 200 : 120;
      brick.insert(brick.end(), {grey, grey, uint8_t(mortar ? 200 : 124)});
    }
  save(dir / "nv_bamboo_desktop.jpg", side, side, 3, bamboo, OIIO::TypeUInt8);
  save(dir / "nv_brick_grey.jpg", side, side, 3, brick, OIIO::TypeUInt8);
}

// ---------------------------------------------------------------- skies

constexpr int kSkyW = 512, kSkyH = 256;

// The sunset sun: elevation 10 degrees, azimuth 45 degrees from the dome's
// +Z towards +X, a disc of 1.5 degrees radius; its radiance is about 5000
// times the brightest sky, so it casts clear shadows.
const float kSunElevation = 10.0f * sdg::kLatLongPi / 180.0f, kSunAzimuth = 45.0f * sdg::kLatLongPi / 180.0f;
const float kSunRadius = 1.5f * sdg::kLatLongPi / 180.0f;
const Vector3f kSunRadiance(8000.0f, 6200.0f, 4200.0f);

Vector3f sunDirection() {
  return {std::cos(kSunElevation) * std::sin(kSunAzimuth), std::sin(kSunElevation),
          std::cos(kSunElevation) * std::cos(kSunAzimuth)};
}

Vector3f lerp(const Vector3f& a, const Vector3f& b, float t) { return a + (b - a) * t; }

// Warm horizon to blue zenith, a glow around the sun, a dim ground.
Vector3f sunsetSky(const Vector3f& d) {
  const float up = d.y();
  if (up < 0) return lerp(Vector3f(0.16f, 0.11f, 0.07f), Vector3f(0.05f, 0.04f, 0.035f), std::min(1.0f, -up * 3));
  const Vector3f horizon(1.5f, 0.72f, 0.34f), zenith(0.10f, 0.20f, 0.55f);
  const float glow = std::pow(std::max(0.0f, d.dot(sunDirection())), 24.0f);
  return lerp(horizon, zenith, std::sqrt(up)) + glow * Vector3f(1.2f, 0.55f, 0.2f);
}

// Brightest at the zenith, (1 + 2 sin(elevation)) / 3 as the CIE overcast
// sky, a grey ground.
Vector3f overcastSky(const Vector3f& d) {
  if (d.y() < 0) return Vector3f(0.12f, 0.12f, 0.115f);
  return Vector3f(0.85f, 0.88f, 0.92f) * ((1 + 2 * d.y()) / 3);
}

// Each pixel the average of 4 x 4 directions across it, so the sun's edge
// is antialiased.
std::vector<float> renderSky(const std::function<Vector3f(const Vector3f&)>& sky, bool withSun) {
  const int n = 4;
  std::vector<float> rgb;
  const Vector3f sun = sunDirection();
  for (int y = 0; y < kSkyH; ++y)
    for (int x = 0; x < kSkyW; ++x) {
      Vector3f sum = Vector3f::Zero();
      for (int sy = 0; sy < n; ++sy)
        for (int sx = 0; sx < n; ++sx) {
          const Vector3f d = sdg::directionFromLatLong((float(x) + (float(sx) + 0.5f) / n) / kSkyW,
                                                       (float(y) + (float(sy) + 0.5f) / n) / kSkyH);
          const bool inSun = withSun && std::acos(std::clamp(d.dot(sun), -1.0f, 1.0f)) < kSunRadius;
          sum += inSun ? kSunRadiance : sky(d);
        }
      sum /= float(n * n);
      rgb.insert(rgb.end(), {sum.x(), sum.y(), sum.z()});
    }
  return rgb;
}

void writeSkies(const fs::path& dir) {
  const auto zip = [](OIIO::ImageSpec& s) { s.attribute("compression", "zip"); };
  const std::vector<float> sunset = renderSky(sunsetSky, true);
  save(dir / "sunset_sky.exr", kSkyW, kSkyH, 3, sunset, OIIO::TypeHalf, zip);
  save(dir / "sunset_sky.hdr", kSkyW, kSkyH, 3, sunset, OIIO::TypeFloat);
  save(dir / "overcast_sky.exr", kSkyW, kSkyH, 3, renderSky(overcastSky, false), OIIO::TypeHalf, zip);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s REPOSITORY_ROOT\n", argv[0]);
    return 2;
  }
  const fs::path root(argv[1]);
  try {
    writeFormats(root / "tests/data/images/formats");
    writeCorrupt(root / "tests/data/images/corrupt");
    writeTextures(root / "scenes/textures");
    writeIsaacPatterns(root / "tests/data/isaac/pack/Isaac/Materials/Textures/Patterns");
    writeSkies(root / "scenes/skies");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
