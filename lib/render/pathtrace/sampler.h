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

// The draws' arithmetic, inline: the path tracer makes eight draws a vertex.
namespace sampler_detail {

constexpr uint32_t reverseBits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  return __builtin_bswap32(x);  // the bytes' order (gcc and clang)
}

// A seeded bijection of 32-bit words in which output bit k depends only on
// input bits 0..k (Laine and Karras 2011): adding, multiplying by an odd
// number and xor-ing with the word times an even number all carry
// information from low bits to high bits only. Applied to bit-reversed
// values it is a nested uniform scramble. The sequence of steps follows
// Burley 2020 and Vegdahl's later refinement (a seed-dependent odd
// multiplier, here passed in: sampler.cpp derives it from the seed); the
// constants are this project's, chosen for flip bits that are unbiased and
// pairwise independent across prefixes to within sampling noise (measured
// over 20000 seeds on the first 7 digit levels).
constexpr uint32_t laineKarrasPermutation(uint32_t x, uint32_t seed, uint32_t oddMultiplier) {
  x ^= x * 0x2a9e6f52u;
  x += seed;
  x *= oddMultiplier;
  x ^= x * 0x7b1c3ad4u;
  x ^= x * 0xd6e8feb6u;
  return x;
}

// Sobol's dimension 1 (Joe-Kuo's second, primitive polynomial x + 1): the
// direction numbers have m_k = 1 for all k by Bratley and Fox's recurrence
// m_k = 2 m_{k-1} xor m_{k-1}, so v_1 = 1/2, v_k = v_{k-1} xor v_{k-1} / 2,
// the rows of Pascal's triangle mod 2.
constexpr uint32_t sobolDimension1(uint32_t index) {
  uint32_t direction = 1u << 31;
  uint32_t result = 0;
  for (; index != 0; index >>= 1, direction ^= direction >> 1)
    if (index & 1u) result ^= direction;
  return result;
}

// The same, bit-reversed, by bytes of the index: the point is the xor of the
// direction numbers of the index's set bits (a linear map over GF(2), as is
// the reversal), so each byte's share can be looked up.
struct ReversedSobol1Tables {
  uint32_t byByte[4][256] = {};
  constexpr ReversedSobol1Tables() {
    for (uint32_t k = 0; k < 4; ++k)
      for (uint32_t b = 0; b < 256; ++b) byByte[k][b] = reverseBits(sobolDimension1(b << (8 * k)));
  }
  constexpr uint32_t operator()(uint32_t index) const {
    return byByte[0][index & 0xffu] ^ byByte[1][(index >> 8) & 0xffu] ^ byByte[2][(index >> 16) & 0xffu] ^
           byByte[3][index >> 24];
  }
};
inline constexpr ReversedSobol1Tables kReversedSobol1{};

// 24 bits: every value is a float exactly, and the largest is below 1.
constexpr float toUnitFloat(uint32_t fixedPoint) { return static_cast<float>(fixedPoint >> 8) * 0x1p-24f; }

}  // namespace sampler_detail

class PixelSampler {
 public:
  PixelSampler(uint64_t frameSeed, uint32_t x, uint32_t y);

  // Starts sample `index` of this pixel; the next draw is its first slot.
  void startSample(uint32_t index) {
    reversedIndex_ = sampler_detail::reverseBits(index);
    slot_ = 0;
  }
  // The next slot's two coordinates, each in [0, 1).
  Vec2f next2D() {
    using namespace sampler_detail;
    const SlotKeys& keys = nextSlot();
    const uint32_t shuffled = shuffledIndex(keys);
    return {toUnitFloat(reverseBits(laineKarrasPermutation(shuffled, keys.x, keys.xMultiplier))),
            toUnitFloat(reverseBits(laineKarrasPermutation(kReversedSobol1(shuffled), keys.y, keys.yMultiplier)))};
  }
  // The next slot's first coordinate, in [0, 1).
  float next1D() {
    using namespace sampler_detail;
    const SlotKeys& keys = nextSlot();
    return toUnitFloat(reverseBits(laineKarrasPermutation(shuffledIndex(keys), keys.x, keys.xMultiplier)));
  }

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
  const SlotKeys& nextSlot() {
    const uint32_t slot = slot_++;
    return slot < cachedSlots_ ? cache_[slot] : workOutSlot(slot);
  }
  const SlotKeys& workOutSlot(uint32_t slot);
  // Scrambling the index (not just the values) shuffles which point each
  // sample gets, so two slots of one sample are not the same point twice;
  // it maps every aligned block of 2^m indices onto another such block, so
  // the nets survive. The formulas, with rev() the bit reversal and LK()
  // laineKarrasPermutation():
  //   shuffled = nestedUniformScramble(index, shuffle) = rev(LK(rev(index), shuffle))
  //   x = nestedUniformScramble(sobol(shuffled, 0), x) = rev(LK(shuffled, x)), as sobol(., 0) = rev()
  //   y = nestedUniformScramble(sobol(shuffled, 1), y) = rev(LK(rev(sobol(shuffled, 1)), y))
  uint32_t shuffledIndex(const SlotKeys& keys) const {
    return sampler_detail::reverseBits(
        sampler_detail::laineKarrasPermutation(reversedIndex_, keys.shuffle, keys.shuffleMultiplier));
  }

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
