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

uint32_t reverseBits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

// A seeded bijection of 32-bit words in which output bit k depends only on
// input bits 0..k (Laine and Karras 2011): adding, multiplying by an odd
// number and xor-ing with the word times an even number all carry
// information from low bits to high bits only. Applied to bit-reversed
// values it is a nested uniform scramble. The sequence of steps follows
// Burley 2020 and Vegdahl's later refinement (a seed-dependent odd
// multiplier); the constants are this project's, chosen for flip bits that
// are unbiased and pairwise independent across prefixes to within sampling
// noise (measured over 20000 seeds on the first 7 digit levels).
uint32_t laineKarrasPermutation(uint32_t x, uint32_t seed) {
  const uint32_t oddMultiplier = static_cast<uint32_t>(mixBits(seed) >> 32) | 1u;
  x ^= x * 0x2a9e6f52u;
  x += seed;
  x *= oddMultiplier;
  x ^= x * 0x7b1c3ad4u;
  x ^= x * 0xd6e8feb6u;
  return x;
}

// 24 bits: every value is a float exactly, and the largest is below 1.
float toUnitFloat(uint32_t fixedPoint) { return static_cast<float>(fixedPoint >> 8) * 0x1p-24f; }

}  // namespace

uint32_t sobol(uint32_t index, int dimension) {
  if (dimension == 0) return reverseBits(index);
  // Direction numbers of x + 1 (m_k = 1 for all k by Bratley and Fox's
  // recurrence m_k = 2 m_{k-1} xor m_{k-1}): v_1 = 1/2, v_k = v_{k-1} xor
  // v_{k-1} / 2, i.e. the rows of Pascal's triangle mod 2.
  uint32_t direction = 1u << 31;
  uint32_t result = 0;
  for (; index != 0; index >>= 1, direction ^= direction >> 1)
    if (index & 1u) result ^= direction;
  return result;
}

uint32_t nestedUniformScramble(uint32_t value, uint32_t seed) {
  return reverseBits(laineKarrasPermutation(reverseBits(value), seed));
}

PixelSampler::PixelSampler(uint64_t frameSeed, uint32_t x, uint32_t y)
    : pixelSeed_(combine(combine(mixBits(frameSeed), x), y)) {}

void PixelSampler::startSample(uint32_t index) {
  index_ = index;
  slot_ = 0;
}

uint32_t PixelSampler::slotSeed() { return static_cast<uint32_t>(combine(pixelSeed_, slot_++)); }

Vec2f PixelSampler::next2D() {
  const uint32_t seed = slotSeed();
  // Scrambling the index (not just the values) shuffles which point each
  // sample gets, so two slots of one sample are not the same point twice;
  // it maps every aligned block of 2^m indices onto another such block, so
  // the nets survive.
  const uint32_t shuffled = nestedUniformScramble(index_, seed);
  return {toUnitFloat(nestedUniformScramble(sobol(shuffled, 0), static_cast<uint32_t>(combine(seed, 1)))),
          toUnitFloat(nestedUniformScramble(sobol(shuffled, 1), static_cast<uint32_t>(combine(seed, 2))))};
}

float PixelSampler::next1D() {
  const uint32_t seed = slotSeed();
  const uint32_t shuffled = nestedUniformScramble(index_, seed);
  return toUnitFloat(nestedUniformScramble(sobol(shuffled, 0), static_cast<uint32_t>(combine(seed, 1))));
}

}  // namespace sdg
