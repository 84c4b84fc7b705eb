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

// MurmurHash3's 32-bit finaliser: every input bit reaches every output bit.
uint32_t mix32(uint32_t h) {
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  return h ^ (h >> 16);
}

using sampler_detail::laineKarrasPermutation;
using sampler_detail::reverseBits;

}  // namespace

uint32_t sobol(uint32_t index, int dimension) {
  return dimension == 0 ? reverseBits(index) : sampler_detail::sobolDimension1(index);
}

uint32_t nestedUniformScramble(uint32_t value, uint32_t seed, uint32_t oddMultiplier) {
  return reverseBits(laineKarrasPermutation(reverseBits(value), seed, oddMultiplier));
}

void SamplerTile::reset(uint64_t frameSeed, uint32_t samplesPerPixel, uint32_t x, uint32_t y) {
  layout_ = SampleLayout(samplesPerPixel);
  tileX_ = x >> layout_.tileBits;
  tileY_ = y >> layout_.tileBits;
  tileSeed_ = combine(combine(mixBits(frameSeed), tileX_), tileY_);
  for (uint32_t slot = 0; slot < kCachedSlots; ++slot) workOut(slot, cache_[slot]);
}

// A slot's eight words: one 64-bit hash of the tile's seed and the slot (a
// SplitMix64 step: the seed advanced by the slot times the golden ratio,
// then mixed) gives the index shuffle's two seeds; 32-bit hashes of those
// give the coordinates' seeds and every hash's odd multiplier. The GPU
// kernel works them out at every draw, where a 64-bit hash is many 32-bit
// operations, so there is only the one.
void SamplerTile::workOut(uint32_t slot, SlotKeys& keys) const {
  const uint64_t seeds = mixBits(tileSeed_ + (uint64_t{slot} + 1) * 0x9e3779b97f4a7c15ull);
  keys.quads = static_cast<uint32_t>(seeds >> 32);
  keys.shuffle = static_cast<uint32_t>(seeds);
  keys.x = mix32(keys.shuffle + 0x632be59bu);
  keys.y = mix32(keys.quads + 0x85157af5u);
  keys.quadsMultiplier = mix32(keys.quads) | 1u;
  keys.shuffleMultiplier = mix32(keys.shuffle) | 1u;
  keys.xMultiplier = mix32(keys.x) | 1u;
  keys.yMultiplier = mix32(keys.y) | 1u;
}

const SamplerTile::SlotKeys& PixelSampler::workOutSlot(uint32_t slot, uint32_t& pixel) {
  const SamplerTile::SlotKeys* keys = &scratch_;
  if (slot < kCachedSlots)
    keys = &tile_->cachedKeys(slot);
  else
    tile_->workOut(slot, scratch_);
  pixel = sampler_detail::permuteQuads(reversedPixel_, quadHighBits_, keys->quads, keys->quadsMultiplier);
  // Slots are drawn in order from 0, so the first draw of a slot below the cache's end is the next one.
  if (slot == cachedSlots_ && slot < kCachedSlots) quads_[cachedSlots_++] = pixel;
  return *keys;
}

}  // namespace sdg
