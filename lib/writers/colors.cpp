#include "writers/colors.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sdg {

std::array<uint8_t, 4> idColor(uint32_t id) {
  if (id == 0) return {0, 0, 0, 0};
  if (id == 1) return {0, 0, 0, 255};
  // 64-bit arithmetic on purpose: a 32-bit hash does not reproduce Replicator.
  uint64_t h = id;
  h ^= h >> 16;
  h *= 0x85EBCA6BULL;
  h ^= h >> 13;
  h *= 0xC2B2AE35ULL;
  h ^= h >> 16;
  double hue = std::fmod(double(id) * (1.0 / 1.618033988749895), 1.0);
  hue = std::fmod(hue + 0.1 * double(h & 0xFFFF) / 65536.0, 1.0);
  const double sat = 0.7 + 0.3 * double((h >> 16) & 0xFF) / 255.0;
  const double val = 0.8 + 0.2 * double((h >> 8) & 0xFF) / 255.0;
  const int sector = int(hue * 6.0) % 6;
  const double f = hue * 6.0 - double(int(hue * 6.0));
  const double p = val * (1 - sat), q = val * (1 - sat * f), t = val * (1 - sat * (1 - f));
  double r = 0, g = 0, b = 0;
  switch (sector) {
    case 0: r = val, g = t, b = p; break;
    case 1: r = q, g = val, b = p; break;
    case 2: r = p, g = val, b = t; break;
    case 3: r = p, g = q, b = val; break;
    case 4: r = t, g = p, b = val; break;
    default: r = val, g = p, b = q; break;
  }
  return {uint8_t(r * 255), uint8_t(g * 255), uint8_t(b * 255), 255};
}

std::string colorKey(const std::array<uint8_t, 4>& c) {
  return "(" + std::to_string(c[0]) + ", " + std::to_string(c[1]) + ", " + std::to_string(c[2]) + ", " +
         std::to_string(c[3]) + ")";
}

std::vector<uint8_t> colorizeDistance(std::span<const float> d) {
  double nearest = std::numeric_limits<double>::infinity(), farthest = -nearest;
  for (float v : d) {
    if (!std::isfinite(v)) continue;
    nearest = std::min(nearest, double(v));
    farthest = std::max(farthest, double(v));
  }
  std::vector<uint8_t> out(d.size(), 0);
  // Nothing finite, or one distance only: the formula is undefined; all dark
  // (documented choice; Replicator's output is platform-dependent there).
  if (!(nearest > 0) || !(farthest > nearest)) return out;
  const double logNear = std::log(nearest), range = std::log(farthest) - logNear;
  for (size_t i = 0; i < d.size(); ++i) {
    if (std::isnan(d[i])) continue;
    double c = std::clamp(double(d[i]), nearest, farthest) + 1e-5;
    double n = (std::log(c) - logNear) / range;
    out[i] = uint8_t(std::clamp((1.0 - n) * 255.0, 0.0, 255.0));  // truncation, as numpy's cast
  }
  return out;
}

}  // namespace sdg
