#pragma once
// RGBA8 images: PNG read (8/16-bit, grey, RGB, RGBA, palette -> RGBA8) and
// written through libpng.
#include <cstdint>
#include <string>
#include <vector>

namespace sdg {

// Documented limits for textures read from disk.
inline constexpr uint32_t kMaxTextureSide = 16384;
inline constexpr uint64_t kMaxTexturePixels = 64ull << 20;  // 64 Mpixel

struct ImageRgba8 {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> pixels;  // rows top to bottom, 4 bytes per pixel
};

// Throws RunError naming the file when it is missing, corrupt or too large.
ImageRgba8 loadPng(const std::string& path);

}  // namespace sdg
