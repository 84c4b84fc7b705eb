#pragma once
// The mip chain of an 8-bit texture, filtered on the CPU (colour in linear light).
// Why not glGenerateMipmap: llvmpipe JIT-compiles a blit shader the first
// time it runs (about 100 ms, more than a whole frame), and a CPU chain is
// the same on every driver.
#include <vector>

#include "assets/image.h"

namespace sdg {

// Levels 1, 2, ... down to 1 x 1 (level 0 is `base` itself), each half the
// previous one's size (rounded down, at least 1) and made from it, as GL
// defines them. Each texel is the area-weighted average of the texels its
// footprint covers: 2 x 2 for even sides, 3 taps where a side is odd. Colour
// is averaged as linear light (the sRGB curve undone, then redone, rounding
// to the nearest code); alpha is averaged as stored.
std::vector<ImageRgba8> srgbMipLevels(const ImageRgba8& base);
// The same for data textures (roughness, metallic, normal and opacity
// maps): every channel averaged as stored.
std::vector<ImageRgba8> linearMipLevels(const ImageRgba8& base);

}  // namespace sdg
