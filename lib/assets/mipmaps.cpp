#include "assets/mipmaps.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace sdg {

namespace {

double srgbCodeToLinear(double code) {
  const double v = code / 255.0;
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

struct SrgbTables {
  std::array<float, 256> linear;       // code -> linear light
  std::array<float, 255> upperBounds;  // linear light where code k rounds up to k + 1
};

const SrgbTables& srgbTables() {
  static const SrgbTables tables = [] {
    SrgbTables t;
    for (int k = 0; k < 256; ++k) t.linear[k] = float(srgbCodeToLinear(k));
    for (int k = 0; k < 255; ++k) t.upperBounds[k] = float(srgbCodeToLinear(k + 0.5));
    return t;
  }();
  return tables;
}

uint8_t linearToSrgbCode(float v, const SrgbTables& t) {
  return uint8_t(std::upper_bound(t.upperBounds.begin(), t.upperBounds.end(), v) - t.upperBounds.begin());
}

// The source texels one destination texel covers along an axis, with the
// fraction of its footprint each takes.
struct Taps {
  uint32_t first = 0;
  int count = 0;
  float weights[3] = {0, 0, 0};
};

std::vector<Taps> tapsFor(uint32_t source, uint32_t target) {
  std::vector<Taps> taps(target);
  const double scale = double(source) / double(target);
  for (uint32_t i = 0; i < target; ++i) {
    const double begin = i * scale, end = (i + 1) * scale;
    Taps& t = taps[i];
    t.first = uint32_t(begin);
    for (uint32_t j = t.first; j < source && double(j) < end && t.count < 3; ++j)
      t.weights[t.count++] = float((std::min(end, j + 1.0) - std::max(begin, double(j))) / scale);
  }
  return taps;
}

// `tables` null: every channel is averaged as stored (data textures).
ImageRgba8 halve(const ImageRgba8& source, const SrgbTables* tables) {
  ImageRgba8 level;
  level.width = std::max(1u, source.width / 2);
  level.height = std::max(1u, source.height / 2);
  level.pixels.resize(size_t(level.width) * level.height * 4);
  const std::vector<Taps> across = tapsFor(source.width, level.width), down = tapsFor(source.height, level.height);
  for (uint32_t y = 0; y < level.height; ++y) {
    const Taps& ty = down[y];
    for (uint32_t x = 0; x < level.width; ++x) {
      const Taps& tx = across[x];
      float sum[4] = {0, 0, 0, 0};
      for (int j = 0; j < ty.count; ++j) {
        const uint8_t* row = source.pixels.data() + size_t(ty.first + j) * source.width * 4;
        for (int i = 0; i < tx.count; ++i) {
          const uint8_t* texel = row + size_t(tx.first + i) * 4;
          const float w = ty.weights[j] * tx.weights[i];
          for (int c = 0; c < 3; ++c) sum[c] += w * (tables ? tables->linear[texel[c]] : float(texel[c]));
          sum[3] += w * float(texel[3]);
        }
      }
      uint8_t* out = level.pixels.data() + (size_t(y) * level.width + x) * 4;
      for (int c = 0; c < 4; ++c) out[c] = uint8_t(std::clamp(std::lround(sum[c]), 0L, 255L));
      if (tables)
        for (int c = 0; c < 3; ++c) out[c] = linearToSrgbCode(sum[c], *tables);
    }
  }
  return level;
}

std::vector<ImageRgba8> mipLevels(const ImageRgba8& base, const SrgbTables* tables) {
  std::vector<ImageRgba8> levels;
  levels.reserve(size_t(std::log2(double(std::max({base.width, base.height, 1u})))) + 1);
  const ImageRgba8* previous = &base;
  while (previous->width > 1 || previous->height > 1) {
    levels.push_back(halve(*previous, tables));
    previous = &levels.back();
  }
  return levels;
}

}  // namespace

std::vector<ImageRgba8> srgbMipLevels(const ImageRgba8& base) { return mipLevels(base, &srgbTables()); }

std::vector<ImageRgba8> linearMipLevels(const ImageRgba8& base) { return mipLevels(base, nullptr); }

}  // namespace sdg
