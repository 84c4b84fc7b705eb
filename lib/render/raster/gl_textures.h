#pragma once
// Creating the GL textures the rasterizer samples and draws into.
#include <vector>

#include "assets/image.h"
#include "render/raster/environment_map.h"
#include "render/raster/gl_api.h"

namespace sdg {

// A colour texture: sRGB storage (sampling returns linear colour), its mip
// chain filtered on the CPU in linear light, trilinear, repeating.
unsigned makeSrgbTexture(const GlApi& gl, const ImageRgba8& image);
// A data texture (roughness, metallic, normal, opacity): stored and
// filtered as plain values, trilinear, repeating.
unsigned makeDataTexture(const GlApi& gl, const ImageRgba8& image);
// A render target or other texture without data, sampled nearest.
unsigned makeTexture(const GlApi& gl, GLint internalFormat, int w, int h, GLenum format, GLenum type);
// Linear RGB floats at half precision (values clamped to its largest,
// 65504), bilinear, repeating across and clamped at the poles: lat-long
// maps. `levels` are the mip chain (one image: no mips).
unsigned makeLatLongTexture(const GlApi& gl, const std::vector<const LatLong*>& levels);
// The dome's own pixels (RGBA floats) for the background, no mips.
unsigned makeLatLongTexture(const GlApi& gl, const ImageRgbaF& image);
// The split-sum table: RG floats, bilinear, clamped.
unsigned makeLutTexture(const GlApi& gl, const SplitSumLut& lut);

}  // namespace sdg
