#include "writers/contact_sheet.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <future>
#include <thread>

#include "assets/image.h"
#include "writers/colors.h"
#include "writers/png_encoder.h"

namespace sdg {
namespace {

constexpr int kGlyphScale = 2;
constexpr int kGap = 4;  // pixels between tiles

// A 3 x 5 pixel font for what labels and frame numbers use; rows top to
// bottom, bit 2 is the left column. Lower case is drawn as upper case.
std::array<uint8_t, 5> glyph(char c) {
  switch (std::toupper(static_cast<unsigned char>(c))) {
    case 'A': return {2, 5, 7, 5, 5};
    case 'B': return {6, 5, 6, 5, 6};
    case 'C': return {3, 4, 4, 4, 3};
    case 'D': return {6, 5, 5, 5, 6};
    case 'E': return {7, 4, 6, 4, 7};
    case 'F': return {7, 4, 6, 4, 4};
    case 'G': return {3, 4, 5, 5, 3};
    case 'H': return {5, 5, 7, 5, 5};
    case 'I': return {7, 2, 2, 2, 7};
    case 'J': return {1, 1, 1, 5, 2};
    case 'K': return {5, 5, 6, 5, 5};
    case 'L': return {4, 4, 4, 4, 7};
    case 'M': return {5, 7, 7, 5, 5};
    case 'N': return {6, 5, 5, 5, 5};
    case 'O': return {2, 5, 5, 5, 2};
    case 'P': return {6, 5, 6, 4, 4};
    case 'Q': return {2, 5, 5, 6, 3};
    case 'R': return {6, 5, 6, 5, 5};
    case 'S': return {3, 4, 2, 1, 6};
    case 'T': return {7, 2, 2, 2, 2};
    case 'U': return {5, 5, 5, 5, 7};
    case 'V': return {5, 5, 5, 5, 2};
    case 'W': return {5, 5, 7, 7, 5};
    case 'X': return {5, 5, 2, 5, 5};
    case 'Y': return {5, 5, 2, 2, 2};
    case 'Z': return {7, 1, 2, 4, 7};
    case '0': return {7, 5, 5, 5, 7};
    case '1': return {2, 6, 2, 2, 7};
    case '2': return {6, 1, 2, 4, 7};
    case '3': return {6, 1, 2, 1, 6};
    case '4': return {5, 5, 7, 1, 1};
    case '5': return {7, 4, 6, 1, 6};
    case '6': return {3, 4, 7, 5, 7};
    case '7': return {7, 1, 2, 2, 2};
    case '8': return {7, 5, 7, 5, 7};
    case '9': return {7, 5, 7, 1, 6};
    case '_': return {0, 0, 0, 0, 7};
    case '-': return {0, 0, 7, 0, 0};
    case '.': return {0, 0, 0, 0, 2};
    case ',': return {0, 0, 0, 2, 4};
    case ':': return {0, 2, 0, 2, 0};
    case ' ': return {0, 0, 0, 0, 0};
    default: return {6, 1, 2, 0, 2};  // '?'
  }
}

struct Canvas {
  int width, height;
  std::vector<uint8_t>& rgb;
  void set(int x, int y, const std::array<uint8_t, 3>& c) {
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    std::copy(c.begin(), c.end(), rgb.begin() + (size_t(y) * size_t(width) + size_t(x)) * 3);
  }
  void fill(int x0, int y0, int x1, int y1, const std::array<uint8_t, 3>& c) {
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) set(x, y, c);
  }
  void rectangle(int x0, int y0, int x1, int y1, const std::array<uint8_t, 3>& c) {
    for (int x = x0; x <= x1; ++x) set(x, y0, c), set(x, y1, c);
    for (int y = y0; y <= y1; ++y) set(x0, y, c), set(x1, y, c);
  }
  // Text on a dark strip, so it reads over any image.
  void text(int x, int y, const std::string& s, const std::array<uint8_t, 3>& c) {
    const int advance = 4 * kGlyphScale;
    fill(x - 1, y - 1, x + advance * int(s.size()), y + 5 * kGlyphScale, {0, 0, 0});
    for (size_t i = 0; i < s.size(); ++i) {
      std::array<uint8_t, 5> rows = glyph(s[i]);
      for (int r = 0; r < 5; ++r)
        for (int col = 0; col < 3; ++col)
          if (rows[size_t(r)] & (4 >> col))
            fill(x + int(i) * advance + col * kGlyphScale, y + r * kGlyphScale,
                 x + int(i) * advance + (col + 1) * kGlyphScale - 1, y + (r + 1) * kGlyphScale - 1, c);
    }
  }
};

// Sheets and tiles are opaque: RGB, a quarter less to compress than RGBA.
std::vector<uint8_t> encodeRgb(const std::vector<uint8_t>& rgb, int width, int height) {
  return encodePng(rgb, uint32_t(width), uint32_t(height), PngPixels::Rgb8, PngOptions::drawing());
}

}  // namespace

std::set<uint64_t> contactSheetFrames(uint64_t frames, size_t maxTiles) {
  std::set<uint64_t> chosen;
  const uint64_t n = std::min<uint64_t>(frames, maxTiles);
  for (uint64_t i = 0; i < n; ++i) chosen.insert(i * frames / n);
  return chosen;
}

std::vector<uint8_t> contactSheetTile(uint64_t frame, const std::vector<uint8_t>& rgba, int width, int height,
                                      const std::vector<SheetBox>& boxes, int tileWidth) {
  struct {
    int width, height;
    std::vector<uint8_t> rgb;
  } tile;
  tile.width = std::min(tileWidth, width);
  tile.height = std::max(1, int(std::lround(double(height) * tile.width / width)));
  tile.rgb.assign(size_t(tile.width) * size_t(tile.height) * 3, 0);
  // Box filter: each thumbnail pixel averages the frame pixels it covers.
  // Column spans are the same on every row: worked out once.
  std::vector<std::pair<int, int>> columns(size_t(tile.width));
  for (int tx = 0; tx < tile.width; ++tx) {
    const int x0 = tx * width / tile.width;
    columns[size_t(tx)] = {x0, std::max(x0 + 1, (tx + 1) * width / tile.width)};
  }
  std::vector<uint32_t> sums(size_t(tile.width) * 3);
  for (int ty = 0; ty < tile.height; ++ty) {
    const int y0 = ty * height / tile.height, y1 = std::max(y0 + 1, (ty + 1) * height / tile.height);
    std::fill(sums.begin(), sums.end(), 0u);
    for (int y = y0; y < y1; ++y) {
      const uint8_t* row = rgba.data() + size_t(y) * size_t(width) * 4;
      for (size_t tx = 0; tx < columns.size(); ++tx)
        for (int x = columns[tx].first; x < columns[tx].second; ++x)
          for (size_t k = 0; k < 3; ++k) sums[tx * 3 + k] += row[size_t(x) * 4 + k];
    }
    uint8_t* out = tile.rgb.data() + size_t(ty) * size_t(tile.width) * 3;
    for (size_t tx = 0; tx < columns.size(); ++tx) {
      const uint32_t count = uint32_t((y1 - y0) * (columns[tx].second - columns[tx].first));
      for (size_t k = 0; k < 3; ++k) out[tx * 3 + k] = uint8_t((sums[tx * 3 + k] + count / 2) / count);
    }
  }
  Canvas canvas{tile.width, tile.height, tile.rgb};
  const double s = double(tile.width) / width;
  // Boxes first, then labels where they do not cover an earlier label, so
  // a crowded frame stays readable (every box is still drawn).
  struct Rect {
    int x0, y0, x1, y1;
  };
  std::vector<Rect> taken;
  for (const SheetBox& b : boxes) {
    std::array<uint8_t, 4> c = idColor(b.semanticId);
    canvas.rectangle(int(b.xMin * s), int(b.yMin * s), int(b.xMax * s), int(b.yMax * s), {c[0], c[1], c[2]});
  }
  for (const SheetBox& b : boxes) {
    std::array<uint8_t, 4> c = idColor(b.semanticId);
    Rect r{int(b.xMin * s) + 1, std::max(1, int(b.yMin * s) - 5 * kGlyphScale - 1), 0, 0};
    r.x1 = r.x0 + 4 * kGlyphScale * int(b.label.size());
    r.y1 = r.y0 + 5 * kGlyphScale;
    bool overlaps = std::any_of(taken.begin(), taken.end(), [&](const Rect& t) {
      return r.x0 <= t.x1 && t.x0 <= r.x1 && r.y0 <= t.y1 && t.y0 <= r.y1;
    });
    if (overlaps) continue;
    taken.push_back(r);
    canvas.text(r.x0, r.y0, b.label, {c[0], c[1], c[2]});
  }
  char number[24];
  std::snprintf(number, sizeof number, "%04llu", static_cast<unsigned long long>(frame));
  canvas.text(2, tile.height - 5 * kGlyphScale - 2, number, {255, 255, 255});
  return encodeRgb(tile.rgb, tile.width, tile.height);
}

std::vector<uint8_t> composeContactSheet(const std::vector<std::string>& tileFiles) {
  struct Tile {
    int width, height;
    std::vector<uint8_t> rgb;
  };
  // The tiles are decoded on several threads (each into its own slot): at
  // the end of a run this is time the user waits for.
  const size_t n = tileFiles.size();
  std::vector<Tile> tiles(n);
  auto decode = [&](size_t i) {
    ImageRgba8 image = loadImageRgba8(tileFiles[i], TextureData::Color);
    Tile t{int(image.width), int(image.height), std::vector<uint8_t>(size_t(image.width) * image.height * 3)};
    for (size_t p = 0; p < size_t(image.width) * image.height; ++p) std::copy_n(&image.pixels[p * 4], 3, &t.rgb[p * 3]);
    tiles[i] = std::move(t);
  };
  const size_t workers = std::min<size_t>(n, std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::future<void>> running;
  for (size_t w = 1; w < workers; ++w)
    running.push_back(std::async(std::launch::async, [&, w] {
      for (size_t i = w; i < n; i += workers) decode(i);
    }));
  for (size_t i = 0; i < n; i += std::max<size_t>(workers, 1)) decode(i);
  for (std::future<void>& r : running) r.get();  // rethrows a worker's failure
  const int columns = std::max(1, int(std::ceil(std::sqrt(double(n)))));
  const int rows = int((n + size_t(columns) - 1) / size_t(columns));
  int cellW = 1, cellH = 1;
  for (const Tile& t : tiles) cellW = std::max(cellW, t.width), cellH = std::max(cellH, t.height);
  const int width = columns * cellW + (columns + 1) * kGap, height = rows * cellH + (rows + 1) * kGap;
  std::vector<uint8_t> rgb(size_t(width) * size_t(height) * 3, 40);
  for (size_t i = 0; i < n; ++i) {
    const Tile& t = tiles[i];
    int ox = kGap + int(i % size_t(columns)) * (cellW + kGap), oy = kGap + int(i / size_t(columns)) * (cellH + kGap);
    for (int y = 0; y < t.height; ++y)
      std::copy_n(t.rgb.begin() + ptrdiff_t(size_t(y) * size_t(t.width) * 3), size_t(t.width) * 3,
                  rgb.begin() + ptrdiff_t((size_t(oy + y) * size_t(width) + size_t(ox)) * 3));
  }
  return encodeRgb(rgb, width, height);
}

}  // namespace sdg
