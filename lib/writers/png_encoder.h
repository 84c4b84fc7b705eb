#pragma once
// PNG encoding into memory with libpng. zlib level 1 with the SUB filter is
// the deliberate default: on rendered frames it is 2-5x faster than level 6
// for files only slightly larger (see the performance notes in the README).
#include <cstdint>
#include <span>
#include <vector>

namespace sdg {

enum class PngPixels { Rgba8, Rgb8, Gray8, Gray16 };

struct PngOptions {
  int zlibLevel = 1;
  // zlib's run-length matching only (Z_RLE). After the SUB filter a rendered
  // image is mostly short runs of small differences that Huffman coding does
  // the work on: the demo's frames come out 20% smaller and encode about 10%
  // faster. Label maps and drawn graphics repeat whole patterns and do better
  // with the full match search.
  bool runLengthOnly = false;

  static PngOptions renderedImage() { return PngOptions{.runLengthOnly = true}; }
};

// `pixels` rows top to bottom, tightly packed; Gray16 samples in host order.
std::vector<uint8_t> encodePng(std::span<const uint8_t> pixels, uint32_t width, uint32_t height, PngPixels format,
                               const PngOptions& options = {});

}  // namespace sdg
