#version 450
// The GPU path tracer's kernel, part 1: buffers, parameters and the sample
// streams. The parts are joined in this order (gpu_path_tracer.cpp):
// pt_common, pt_bsdf, pt_scene, pt_lights, pt_trace. Each is a port of the
// CPU tracer's file named in its header; keep the two in step.
layout(local_size_x = 8, local_size_y = 4) in;

// The stage's features, defined by gpu_path_tracer.cpp before this part
// (gpu_scene.h's GpuKernelFeatures): the kernel is compiled for those the
// frame's stage has, so what it lacks is no code at all. Fewer registers a
// thread, more threads at work: on an H100 the demo's frame took 3.0 ms
// with its own features against 5.4 with all.
const bool kDomeMaps = SDG_DOME_MAPS != 0;               // a dome light with a map
const bool kOpacity = SDG_OPACITY != 0;                  // a material with an opacity (cut-outs)
const bool kNormalMaps = SDG_NORMAL_MAPS != 0;           // a material with a normal map
const bool kTriplanar = SDG_TRIPLANAR != 0;              // a material projected triplanar
const bool kLobeMultipliers = SDG_LOBE_MULTIPLIERS != 0; // a light's inputs:diffuse or inputs:specular not 1
const bool kSphereLights = SDG_SPHERE_LIGHTS != 0;       // a sphere light
const bool kShapeLights = SDG_SHAPE_LIGHTS != 0;         // a rect, disk or cylinder light
const bool kDistantLights = SDG_DISTANT_LIGHTS != 0;     // a distant light
const bool kDomeLights = SDG_DOME_LIGHTS != 0;           // a dome light
const bool kBaseColorMaps = SDG_BASE_COLOR_MAPS != 0;    // a material with a base colour map
const bool kSurfaceMaps = SDG_SURFACE_MAPS != 0;         // a material with a roughness or metallic map
const bool kVertexColors = SDG_VERTEX_COLORS != 0;       // a material times the mesh's vertex colours

const float kPi = 3.14159265358979323846;
const float kInf = uintBitsToFloat(0x7f800000u);
const float kOneBelowOne = uintBitsToFloat(0x3f7fffffu);  // 0x1.fffffep-1

// One frame's inputs (gpu_frame.cpp writes them, std430), then the float
// tables: pt_textures.cpp's sRGB table (256 entries from 0), the lights'
// pick cdf and the dome's sampling tables, at the offsets given here.
// Sixteen storage blocks is the most a driver must offer, so related arrays
// share one.
layout(std430, binding = 0) readonly buffer Params {
  vec4 camNear0, camNearX, camNearY;  // the near-plane point at pixel (0, 0) and its change per pixel, world
  vec4 camFar0, camFarX, camFarY;     // the same on the far plane
  vec4 eye;
  ivec4 size;        // width, height, first sample, samples in this dispatch
  ivec4 counts;      // max bounces, light count, instance count, 1 where a light scales the BSDF's lobes apart
  uvec4 seed;        // frame seed (low, high), top-level root item, label pass (1: write the labels)
  ivec4 dome;        // width, height (0: no map), first texel (uint words in `texels`), pick cdf offset
  ivec4 domeTables;  // offsets: row cdf, column cdfs, row cosines, texel solid angles
  uvec4 sampling;    // the frame's samples per pixel, its SampleLayout (sampler.h: sample bits, tile bits), 0
  float tables[];
} params;

// The film, per pixel: the running sum (rgb; w: samples dropped), the
// label planes, the rays traced. Each pixel is written by its own
// invocation only, in sample order: no atomics, nothing summed across pixels.
struct FilmPixel {
  vec4 sum;
  vec4 albedo;       // rgb; w: the samples' sum of squared luminance
  vec4 normalDepth;  // xyz, depth
  uvec4 rays;        // rays traced (low, high), camera rays, the instance id
};
layout(std430, binding = 1) buffer Film { FilmPixel film[]; };

// --- 64-bit words as uvec2 (low, high): the sampler's hashes are 64-bit. ---
uvec2 xor64(uvec2 a, uvec2 b) { return a ^ b; }
uvec2 shr64(uvec2 a, int n) {  // 0 < n < 32
  return uvec2((a.x >> uint(n)) | (a.y << uint(32 - n)), a.y >> uint(n));
}
uvec2 mul64(uvec2 a, uvec2 b) {
  uint hi, lo;
  umulExtended(a.x, b.x, hi, lo);
  hi += a.x * b.y + a.y * b.x;
  return uvec2(lo, hi);
}
uvec2 add64(uvec2 a, uvec2 b) {
  uint carry;
  uint lo = uaddCarry(a.x, b.x, carry);
  return uvec2(lo, a.y + b.y + carry);
}

// sampler.cpp's mixBits (SplitMix64's finaliser) and combine.
uvec2 mixBits(uvec2 z) {
  z = xor64(z, shr64(z, 30));
  z = mul64(z, uvec2(0x1ce4e5b9u, 0xbf58476du));
  z = xor64(z, shr64(z, 27));
  z = mul64(z, uvec2(0x133111ebu, 0x94d049bbu));
  return xor64(z, shr64(z, 31));
}
uvec2 combine(uvec2 seed, uvec2 value) { return mixBits(xor64(seed, mixBits(add64(value, uvec2(0x7f4a7c15u, 0x9e3779b9u))))); }

uint laineKarrasPermutation(uint x, uint seed, uint oddMultiplier) {
  x ^= x * 0x2a9e6f52u;
  x += seed;
  x *= oddMultiplier;
  x ^= x * 0x7b1c3ad4u;
  x ^= x * 0xd6e8feb6u;
  return x;
}
// sampler.h's permuteQuads: each Morton digit's quad of sub-blocks handed to its pixels by any of 24 permutations.
uint permuteQuads(uint reversed, uint highBits, uint seed, uint oddMultiplier) {
  uint random = laineKarrasPermutation(reversed, seed, oddMultiplier) ^ reversed;
  uint byX = random & highBits, diagonal = (random << 1) & highBits;
  uint y = reversed & highBits, x = (reversed >> 1) & highBits;
  uint picked = (x & byX) | (y & ~byX), other = x ^ y ^ picked;
  return (reversed & ~(highBits | (highBits << 1))) | (picked ^ (diagonal & other)) | (other << 1);
}
// Sobol's second dimension, bit-reversed (sampler.h's kReversedSobol1; the
// first is the reversed index itself). Its generator is Pascal's triangle
// mod 2: by Lucas' theorem index bit k reaches result bit 31 - j when j's
// bits are a subset of k's, so the product is the superset XOR transform of
// the index's bits, five shift-and-xor steps (a loop over the index's bits
// ran up to 32 times here, as the scrambled index's high bits are random).
uint reversedSobol1(uint index) {
  uint y = index;
  y ^= (y >> 1) & 0x55555555u;
  y ^= (y >> 2) & 0x33333333u;
  y ^= (y >> 4) & 0x0f0f0f0fu;
  y ^= (y >> 8) & 0x00ff00ffu;
  y ^= (y >> 16) & 0x0000ffffu;
  return y;
}
float toUnitFloat(uint fixedPoint) { return float(fixedPoint >> 8) * (1.0 / 16777216.0); }

// sampler.h's Morton code: x's bits in the even bits, y's in the odd ones.
uint spreadBits(uint v) {
  v &= 0xffffu;
  v = (v | (v << 8)) & 0x00ff00ffu;
  v = (v | (v << 4)) & 0x0f0f0f0fu;
  v = (v | (v << 2)) & 0x33333333u;
  return (v | (v << 1)) & 0x55555555u;
}

// sampler.h's PixelSampler with its SamplerTile's keys: the same stream as
// the CPU's for (seed, samples per pixel, x, y, sample, slot). The keys are
// hashed at each draw (a per-invocation cache of them went to local memory:
// docs/performance.md); the tile's seed and the pixel's first index once.
struct Sampler {
  uvec2 tileSeed;
  uint indexBase;    // the pixel's first Sobol index: its Morton code in the tile, above the sample bits
  uint highBits;     // SampleLayout::quadHighBits
  uint reversed;     // the sample's Sobol index, bit-reversed
  uint slot;
};
// bits: sampler.h's SampleLayout (sample bits, tile bits) for the frame's samples per pixel.
Sampler pixelSampler(uvec2 frameSeed, uint x, uint y, uvec2 bits) {
  Sampler s;
  s.tileSeed = combine(combine(mixBits(frameSeed), uvec2(x >> bits.y, 0u)), uvec2(y >> bits.y, 0u));
  uint mask = (1u << bits.y) - 1u;
  s.indexBase = bits.x >= 32u ? 0u : (spreadBits(x & mask) | (spreadBits(y & mask) << 1)) << bits.x;
  s.highBits = bits.y == 0u ? 0u : (0x55555555u & ((1u << (2u * bits.y)) - 1u)) << (32u - bits.x - 2u * bits.y);
  s.reversed = 0u;
  s.slot = 0u;
  return s;
}
void startSample(inout Sampler s, uint index) {
  s.reversed = bitfieldReverse(s.indexBase | index);
  s.slot = 0u;
}
// sampler.cpp's mix32 (MurmurHash3's 32-bit finaliser).
uint mix32(uint h) {
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  return h ^ (h >> 16);
}
// The slot's shuffled index (SamplerTile::workOut's keys, worked out here at
// each draw); seeds: the index shuffle's two seeds, whose hashes seed the coordinates.
uint shuffledIndex(inout Sampler s, out uvec2 seeds) {
  s.slot++;
  seeds = mixBits(add64(s.tileSeed, mul64(uvec2(s.slot, 0u), uvec2(0x7f4a7c15u, 0x9e3779b9u))));
  uint quads = permuteQuads(s.reversed, s.highBits, seeds.y, mix32(seeds.y) | 1u);
  return bitfieldReverse(laineKarrasPermutation(quads, seeds.x, mix32(seeds.x) | 1u));
}
float scrambledCoordinate(uint reversedValue, uint seed) {
  return toUnitFloat(bitfieldReverse(laineKarrasPermutation(reversedValue, seed, mix32(seed) | 1u)));
}
vec2 next2D(inout Sampler s) {
  uvec2 seeds;
  uint shuffled = shuffledIndex(s, seeds);
  return vec2(scrambledCoordinate(shuffled, mix32(seeds.x + 0x632be59bu)),
              scrambledCoordinate(reversedSobol1(shuffled), mix32(seeds.y + 0x85157af5u)));
}
float next1D(inout Sampler s) {
  uvec2 seeds;
  uint shuffled = shuffledIndex(s, seeds);
  return scrambledCoordinate(shuffled, mix32(seeds.x + 0x632be59bu));
}

float luminance(vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }
float maxComponent(vec3 v) { return max(v.x, max(v.y, v.z)); }
