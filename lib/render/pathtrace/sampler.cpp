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

// Four 64-bit hashes give the eight words: a seed and an odd multiplier for
// each of the four hashes a draw makes (the GPU kernel works them out at
// every draw, so they are as few as that allows).
void SamplerTile::workOut(uint32_t slot, SlotKeys& keys) const {
  const uint64_t seeds = combine(tileSeed_, slot);
  const uint64_t multipliers = combine(seeds, 0), x = combine(seeds, 1), y = combine(seeds, 2);
  keys.quads = static_cast<uint32_t>(seeds >> 32);
  keys.quadsMultiplier = static_cast<uint32_t>(multipliers >> 32) | 1u;
  keys.shuffle = static_cast<uint32_t>(seeds);
  keys.shuffleMultiplier = static_cast<uint32_t>(multipliers) | 1u;
  keys.x = static_cast<uint32_t>(x);
  keys.xMultiplier = static_cast<uint32_t>(x >> 32) | 1u;
  keys.y = static_cast<uint32_t>(y);
  keys.yMultiplier = static_cast<uint32_t>(y >> 32) | 1u;
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
