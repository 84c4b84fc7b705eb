#include "behavior/rng.h"

namespace sdg {

Rng::Rng(uint64_t seed, uint64_t stream) {
  // PCG's seeding: the increment must be odd; advance once before and after
  // adding the seed so nearby seeds give unrelated streams.
  increment_ = (stream << 1u) | 1u;
  state_ = 0;
  nextU32();
  state_ += seed;
  nextU32();
}

uint32_t Rng::nextU32() {
  uint64_t old = state_;
  state_ = old * 6364136223846793005ULL + increment_;
  auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
  auto rot = static_cast<uint32_t>(old >> 59u);
  return (xorshifted >> rot) | (xorshifted << ((-rot) & 31u));
}

double Rng::uniform01() {
  uint64_t hi = nextU32() >> 5;  // 27 bits
  uint64_t lo = nextU32() >> 6;  // 26 bits
  return static_cast<double>((hi << 26) | lo) * (1.0 / 9007199254740992.0);  // / 2^53
}

int64_t Rng::integers(int64_t low, int64_t highExclusive) {
  if (highExclusive <= low) return low;
  uint64_t range = static_cast<uint64_t>(highExclusive - low);
  // Rejection sampling on 64 random bits: no modulo bias.
  uint64_t limit = UINT64_MAX - (UINT64_MAX % range);
  while (true) {
    uint64_t r = (static_cast<uint64_t>(nextU32()) << 32) | nextU32();
    if (r < limit) return low + static_cast<int64_t>(r % range);
  }
}

uint64_t mix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

uint64_t stableHash(std::string_view text, uint64_t seed) {
  uint64_t h = 0xCBF29CE484222325ULL ^ mix64(seed);
  for (unsigned char c : text) {
    h ^= c;
    h *= 0x100000001B3ULL;
  }
  return mix64(h);
}

Rng makeBehaviorRng(int64_t runSeed, std::string_view primPath, std::string_view behavior, uint64_t iteration,
                    int32_t fixedSeed) {
  if (fixedSeed >= 0) {
    uint64_t seed = mix64(static_cast<uint64_t>(fixedSeed));
    return Rng(seed, stableHash(behavior));
  }
  uint64_t seed = stableHash(primPath, stableHash(behavior, mix64(static_cast<uint64_t>(runSeed)) ^ mix64(iteration + 1)));
  return Rng(seed, stableHash(primPath, 0x5D6B));
}

}  // namespace sdg
