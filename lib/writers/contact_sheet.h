#pragma once
// contact_sheet.png: a grid of thumbnails of the captured frames (the first
// render product) with each labelled entity's tight box and class name
// drawn, so a user sees the dataset at a glance. At most `maxTiles` frames,
// spread evenly over the run; frames are added in order on one thread, so
// the sheet's bytes depend only on the frames.
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

class ContactSheet {
 public:
  ContactSheet(uint64_t frames, int tileWidth = 256, size_t maxTiles = 36);

  bool wants(uint64_t frame) const { return chosen_.count(frame) != 0; }
  // `rgba`: width x height, 4 bytes per pixel, rows top to bottom.
  void add(uint64_t frame, const std::vector<uint8_t>& rgba, int width, int height, const std::vector<SheetBox>& boxes);
  bool empty() const { return tiles_.empty(); }
  std::vector<uint8_t> encodePng() const;

 private:
  struct Tile {
    uint64_t frame;
    int width, height;
    std::vector<uint8_t> rgb;
  };
  std::set<uint64_t> chosen_;
  int tileWidth_;
  std::vector<Tile> tiles_;
};

}  // namespace sdg
