#pragma once
// contact_sheet.png: a grid of thumbnails of the captured frames (the first
// render product) with each labelled entity's tight box and class name
// drawn, so a user sees the dataset at a glance. At most 36 frames, spread
// evenly over the run. Each thumbnail is its own small PNG written with its
// frame; the grid is composed from those files at the end, so a whole run,
// a resumed one and merged shards give the same sheet.
#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace sdg {

struct SheetBox {
  int xMin = 0, yMin = 0, xMax = 0, yMax = 0;  // inclusive pixels of the full frame
  uint32_t semanticId = 0;                      // picks the box colour
  std::string label;
};

inline constexpr size_t kContactSheetTiles = 36;
inline constexpr int kContactSheetTileWidth = 256;

// The frames the sheet shows for a run of `frames` frames.
std::set<uint64_t> contactSheetFrames(uint64_t frames, size_t maxTiles = kContactSheetTiles);

// One thumbnail with boxes, labels and the frame number, as PNG bytes.
// `rgba`: width x height, 4 bytes per pixel, rows top to bottom.
std::vector<uint8_t> contactSheetTile(uint64_t frame, const std::vector<uint8_t>& rgba, int width, int height,
                                      const std::vector<SheetBox>& boxes, int tileWidth = kContactSheetTileWidth);

// The grid of the tiles (PNG files, in frame order) as PNG bytes.
std::vector<uint8_t> composeContactSheet(const std::vector<std::string>& tileFiles);

}  // namespace sdg
