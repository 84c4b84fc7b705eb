#pragma once
// Coverage masks as the rasterizer reads them back: every entity drawn as if
// alone, one bit per (pixel, entity). Plain data, so the write pool (loose
// boxes, occlusion, BOP's full-silhouette masks) reads them without GL.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace sdg {

// One width x height layer of bits per 32 groups (group g is bit g % 32 of
// layer g / 32), rows bottom first, as GL gives them.
struct CoverageMasks {
  int width = 0, height = 0;
  size_t groups = 0;
  std::vector<uint32_t> bits;

  // Whether group `group` covers pixel (x, y), y counted from the top row.
  bool covers(size_t group, int x, int y) const {
    const size_t layerWords = size_t(width) * size_t(height);
    const size_t at = (group / 32) * layerWords + size_t(height - 1 - y) * size_t(width) + size_t(x);
    return (bits[at] >> (group % 32)) & 1u;
  }
};

// How many pixels a group covers and its pixel bounds (inclusive; all zero
// with xMax -1 when it covers none).
struct MaskCoverage {
  uint64_t pixels = 0;
  int xMin = 0, yMin = 0, xMax = -1, yMax = -1;
};

void coverageOfMasks(const CoverageMasks& masks, std::vector<MaskCoverage>& out);

}  // namespace sdg
