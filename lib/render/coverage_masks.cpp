#include "render/coverage_masks.h"

#include <algorithm>

namespace sdg {

void coverageOfMasks(const CoverageMasks& masks, std::vector<MaskCoverage>& out) {
  const int w = masks.width, h = masks.height;
  out.assign(masks.groups, MaskCoverage{});
  for (auto& c : out) {
    c.xMin = w;
    c.yMin = h;
  }
  const size_t layerWords = size_t(w) * size_t(h);
  for (size_t layer = 0; layer * 32 < masks.groups; ++layer) {
    const uint32_t* pixels = masks.bits.data() + layer * layerWords;
    for (int glY = 0; glY < h; ++glY) {
      const uint32_t* row = pixels + size_t(glY) * size_t(w);
      const int y = h - 1 - glY;  // rows top to bottom
      // A row is long runs of one mask (mostly 0): each run's groups are
      // updated once, not once per pixel.
      for (int x = 0; x < w;) {
        const uint32_t mask = row[x];
        int end = x + 1;
        while (end < w && row[end] == mask) ++end;
        for (uint32_t bits = mask; bits; bits &= bits - 1) {
          MaskCoverage& c = out[layer * 32 + size_t(__builtin_ctz(bits))];
          c.pixels += uint64_t(end - x);
          c.xMin = std::min(c.xMin, x);
          c.xMax = std::max(c.xMax, end - 1);
          c.yMin = std::min(c.yMin, y);
          c.yMax = std::max(c.yMax, y);
        }
        x = end;
      }
    }
  }
  for (auto& c : out)
    if (!c.pixels) c = MaskCoverage{};
}

}  // namespace sdg
