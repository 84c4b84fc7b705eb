#version 450
// The frame as a run writes it, made on the device: the film's radiance
// (the mean of its samples, or the denoiser's output) through the
// rasterizer's tone curve into RGBA8, and on request the linear radiance
// itself, so a run reads back 1 MB of a 512 x 512 frame (4 with the
// radiance) instead of the 16 MB film, and the CPU does not tone map.
// path_tracer.cpp's toneMap() is the CPU's form; the two agree within one
// code value (the device's exp and pow round differently).
layout(local_size_x = 8, local_size_y = 8) in;

struct FilmPixel {
  vec4 sum;
  vec4 albedo;
  vec4 normalDepth;
  uvec4 rays;
};
layout(std430, binding = 1) readonly buffer Film { FilmPixel film[]; };
// RGBA8 per pixel (red in the low byte), then, with `withRadiance`, three
// floats per pixel as their bits.
layout(std430, binding = 13) writeonly buffer Display { uint display[]; };

uniform int width, height, withRadiance;
uniform float radianceDivisor;  // the samples for a sum, 1 for the denoiser's output
uniform float exposureScale;

uint toByte(float radiance) {
  float mapped = 1.0 - exp(-radiance * exposureScale);
  float srgb = mapped <= 0.0031308 ? mapped * 12.92 : 1.055 * pow(mapped, 1.0 / 2.4) - 0.055;
  float clamped = isnan(srgb) ? 0.0 : clamp(srgb, 0.0, 1.0);
  return uint(floor(clamped * 255.0 + 0.5));
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= uint(width) || pixel.y >= uint(height)) return;
  uint index = pixel.y * uint(width) + pixel.x;
  vec3 radiance = film[index].sum.xyz / radianceDivisor;
  display[index] = toByte(radiance.x) | (toByte(radiance.y) << 8) | (toByte(radiance.z) << 16) | (255u << 24);
  if (withRadiance != 0) {
    uint at = uint(width) * uint(height) + 3u * index;
    display[at] = floatBitsToUint(radiance.x);
    display[at + 1u] = floatBitsToUint(radiance.y);
    display[at + 2u] = floatBitsToUint(radiance.z);
  }
}
