#pragma once
// PNG encoding into memory with libpng, always at zlib level 1: 2-5x faster
// than level 6 for files only slightly larger. The row filter and zlib's
// matching are chosen per kind of image; each preset below was measured on
// the demo's outputs (see the performance notes in the README).
#include <cstdint>
#include <span>
#include <vector>

namespace sdg {

enum class PngPixels { Rgba8, Rgb8, Gray8, Gray16 };
enum class PngFilter { None, Sub, Up };

struct PngOptions {
  int zlibLevel = 1;
  PngFilter filter = PngFilter::Sub;
  // zlib's run-length matching only (Z_RLE) instead of its full search.
  bool runLengthOnly = false;

  // Shaded pictures (rgb, normals, colourised depth): after SUB they are
  // short runs of small differences that Huffman coding does the work on;
  // run-length matching makes the demo's frames 20% smaller, 10% faster.
  static PngOptions renderedImage() { return {1, PngFilter::Sub, true}; }
  // Label maps (segmentations): flat regions repeat from row to row, which
  // UP turns into zeros; 15-20% smaller than SUB, a little faster.
  static PngOptions labelMap() { return {1, PngFilter::Up, false}; }
  // Drawings (the contact sheet and its tiles): flat fills, outlines and
  // text repeat as they are; unfiltered they come out 15% smaller and
  // encode 20-30% faster than with SUB.
  static PngOptions drawing() { return {1, PngFilter::None, false}; }
};

// `pixels` rows top to bottom, tightly packed; Gray16 samples in host order.
std::vector<uint8_t> encodePng(std::span<const uint8_t> pixels, uint32_t width, uint32_t height, PngPixels format,
                               const PngOptions& options = {});

}  // namespace sdg
