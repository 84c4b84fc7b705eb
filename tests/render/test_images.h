#pragma once
// Images the render tests write themselves, so they control every texel:
// a Radiance .hdr (flat RGBE scanlines, top row first) and an RGBA8 PNG.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <vector>

#include "stage/math_types.h"
#include "writers/png_encoder.h"

namespace sdg::test {

inline void writeRgbe(const std::filesystem::path& file, int w, int h,
                      const std::function<Vec3f(int x, int y)>& texel) {
  std::ofstream out(file, std::ios::binary);
  out << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " << h << " +X " << w << "\n";
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Vec3f c = texel(x, y);
      const float v = std::max({c.x(), c.y(), c.z()});
      unsigned char rgbe[4] = {0, 0, 0, 0};
      if (v > 1e-32f) {
        int e = 0;
        const float scale = std::frexp(v, &e) * 256.0f / v;
        for (int k = 0; k < 3; ++k) rgbe[k] = static_cast<unsigned char>(c[k] * scale);
        rgbe[3] = static_cast<unsigned char>(e + 128);
      }
      out.write(reinterpret_cast<const char*>(rgbe), 4);
    }
}

// The dome orientation tests' 64 x 32 map: sectors by longitude (OpenEXR:
// u = 0.25 looks along the dome's +X, 0.5 along +Z, 0.75 along -X) at value
// 4 in red, green, blue and white (-Z), a yellow cap at the pole (top 8
// rows) and grey 0.5 below the bottom 8.
inline void writeSectorSky(const std::filesystem::path& file) {
  writeRgbe(file, 64, 32, [](int x, int y) {
    if (y < 8) return Vec3f(4, 4, 0);
    if (y >= 24) return Vec3f(0.5f, 0.5f, 0.5f);
    if (x >= 8 && x < 24) return Vec3f(4, 0, 0);
    if (x >= 24 && x < 40) return Vec3f(0, 4, 0);
    if (x >= 40 && x < 56) return Vec3f(0, 0, 4);
    return Vec3f(4, 4, 4);
  });
}

inline void writePng(const std::filesystem::path& file, int w, int h,
                     const std::function<std::array<uint8_t, 4>(int x, int y)>& texel) {
  std::vector<uint8_t> rgba(size_t(w) * size_t(h) * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const auto c = texel(x, y);
      std::copy(c.begin(), c.end(), rgba.begin() + (ptrdiff_t(y) * w + x) * 4);
    }
  const std::vector<uint8_t> png = encodePng(rgba, uint32_t(w), uint32_t(h), PngPixels::Rgba8);
  std::ofstream(file, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
}

}  // namespace sdg::test
