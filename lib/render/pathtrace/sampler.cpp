#include "render/pathtrace/sampler.h"

namespace sdg {
namespace {

// A 64-bit finaliser (xor-shift-multiply, SplitMix64's constants): every
// input bit reaches every output bit, so nearby pixels and slots get
// unrelated seeds.
uint64_t mixBits(uint64_t z) {
  z ^= z >> 30;
  z *= 0xbf58476d1ce4e5b9ull;
  z ^= z >> 27;
  z *= 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

uint64_t combine(uint64_t seed, uint64_t value) { return mixBits(seed ^ mixBits(value + 0x9e3779b97f4a7c15ull)); }

using sampler_detail::laineKarrasPermutation;
using sampler_detail::reverseBits;

// The odd multiplier laineKarrasPermutation takes with `seed`.
uint32_t oddMultiplierOf(uint32_t seed) { return static_cast<uint32_t>(mixBits(seed) >> 32) | 1u; }

uint32_t laineKarrasPermutation(uint32_t x, uint32_t seed) {
  return laineKarrasPermutation(x, seed, oddMultiplierOf(seed));
}

}  // namespace

uint32_t sobol(uint32_t index, int dimension) {
  return dimension == 0 ? reverseBits(index) : sampler_detail::sobolDimension1(index);
}

uint32_t nestedUniformScramble(uint32_t value, uint32_t seed) {
  return reverseBits(laineKarrasPermutation(reverseBits(value), seed));
}

void SamplerTile::reset(uint64_t frameSeed, uint32_t samplesPerPixel, uint32_t x, uint32_t y) {
  layout_ = SampleLayout(samplesPerPixel);
  tileX_ = x >> layout_.tileBits;
  tileY_ = y >> layout_.tileBits;
  tileSeed_ = combine(combine(mixBits(frameSeed), tileX_), tileY_);
  cachedSlots_ = 0;
}

void SamplerTile::workOut(uint32_t slot, SlotKeys& keys) const {
  const uint32_t seed = static_cast<uint32_t>(combine(tileSeed_, slot));
  keys.shuffle = seed;
  keys.x = static_cast<uint32_t>(combine(seed, 1));
  keys.y = static_cast<uint32_t>(combine(seed, 2));
  keys.shuffleMultiplier = oddMultiplierOf(keys.shuffle);
  keys.xMultiplier = oddMultiplierOf(keys.x);
  keys.yMultiplier = oddMultiplierOf(keys.y);
}

const SamplerTile::SlotKeys& SamplerTile::workOutSlot(uint32_t slot) {
  if (slot >= kCachedSlots) {
    workOut(slot, scratch_);
    return scratch_;
  }
  // Samplers draw slot k after slot k - 1, so this loop runs once; the cache stays a prefix whatever the order.
  for (; cachedSlots_ <= slot; ++cachedSlots_) workOut(cachedSlots_, cache_[cachedSlots_]);
  return cache_[slot];
}

}  // namespace sdg
