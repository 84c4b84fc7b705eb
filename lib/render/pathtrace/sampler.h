#pragma once
// Low-discrepancy sample streams for the path tracer, one per pixel:
// Owen-scrambled Sobol points padded in dimension pairs, after Burley 2020,
// "Practical Hash-based Owen Scrambling".
//
// Every draw (a next2D() pair or a next1D() value) takes the next
// "dimension slot" of the sample. Each slot uses the first two Sobol
// dimensions, which form a (0,2)-sequence in base 2, with
// - its own shuffle of the sample index (a nested uniform scramble of the
//   index), so slots are decorrelated from one another, and
// - its own nested uniform (Owen) scramble of each coordinate, done with a
//   Laine-Karras style hash, so pixels and frames are decorrelated.
// Both scrambles keep the net structure: the samples [k 2^m, (k+1) 2^m) of a
// slot form a (0,m,2)-net, so every elementary interval of area 2^-m holds
// exactly one point.
//
// A stream depends only on (frame seed, pixel x, y, sample index, slot):
// never on the thread that draws it nor on the order pixels are drawn.
// The GPU tracer draws the same numbers (gpu/shaders/pt_common.glsl).
//
// Speed: a slot's hashed seeds depend on the pixel and the slot, not on the
// sample, so a sampler works them out once for its pixel's first
// kCachedSlots slots and every later sample reuses them; Sobol's second
// dimension comes from byte tables. Both give exactly the numbers of the
// plain formulas (sobol(), nestedUniformScramble()).
#include <cstdint>

#include "stage/math_types.h"

namespace sdg {

class PixelSampler {
 public:
  PixelSampler(uint64_t frameSeed, uint32_t x, uint32_t y);

  // Starts sample `index` of this pixel; the next draw is its first slot.
  void startSample(uint32_t index);
  // The next slot's two coordinates, each in [0, 1).
  Vec2f next2D();
  // The next slot's first coordinate, in [0, 1).
  float next1D();

  // Slots whose seeds a sampler keeps: a path of the default 8 bounces
  // draws 41.
  static constexpr uint32_t kCachedSlots = 48;

 private:
  // A slot's scramble keys: the seed of the index shuffle and of each
  // coordinate's scramble, each with the odd multiplier its hash derives
  // from it.
  struct SlotKeys {
    uint32_t shuffle, shuffleMultiplier;
    uint32_t x, xMultiplier;
    uint32_t y, yMultiplier;
  };
  const SlotKeys& nextSlot();
  // The shuffled sample index for `keys`, bit-reversed and not.
  uint32_t shuffledIndex(const SlotKeys& keys) const;

  uint64_t pixelSeed_;
  uint32_t reversedIndex_ = 0;
  uint32_t slot_ = 0;
  uint32_t cachedSlots_ = 0;  // slots [0, cachedSlots_) of cache_ are worked out
  SlotKeys scratch_;          // a slot beyond the cache
  SlotKeys cache_[kCachedSlots];
};

// The building blocks, exposed for the tests.

// Sobol point `index` in dimension 0 (van der Corput) or 1 (Joe-Kuo's
// second dimension, primitive polynomial x + 1), as a 0.32 fixed-point value.
uint32_t sobol(uint32_t index, int dimension);

// Owen's nested uniform scramble of a 0.32 fixed-point value: digit k (from
// the most significant) is flipped by a pseudo-random function of the seed
// and the digits above it only.
uint32_t nestedUniformScramble(uint32_t value, uint32_t seed);

}  // namespace sdg
