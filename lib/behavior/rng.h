#pragma once
// Portable random streams: PCG32 (O'Neill's pcg32 XSH-RR 64/32) with the
// project's own transforms to doubles, integers and choices, so draws are
// identical on every platform and standard library. Never std:: distributions.
#include <cstdint>
#include <span>
#include <string_view>

namespace sdg {

class Rng {
 public:
  Rng() : Rng(0, 0) {}
  Rng(uint64_t seed, uint64_t stream);

  uint32_t nextU32();
  // u in [0, 1) with 53 random bits.
  double uniform01();
  // low + (high - low) * u, as numpy's Generator.uniform; works for low > high too.
  double uniform(double low, double high) { return low + (high - low) * uniform01(); }
  // Uniform integer in [low, highExclusive); unbiased (rejection).
  int64_t integers(int64_t low, int64_t highExclusive);
  size_t index(size_t count) { return static_cast<size_t>(integers(0, static_cast<int64_t>(count))); }
  bool bernoulli(double p) { return uniform01() < p; }

 private:
  uint64_t state_ = 0;
  uint64_t increment_ = 1;
};

// Stable 64-bit hash of text (FNV-1a), mixed with SplitMix64; the same on
// every machine, used to derive stream seeds from names.
uint64_t stableHash(std::string_view text, uint64_t seed = 0);
uint64_t mix64(uint64_t x);

// The stream of one (behavior, prim): from the run seed, the prim path, the
// behavior namespace and the iteration; or, when the behavior's `seed`
// variable is >= 0, from that seed and the namespace alone (so a fixed seed
// replays the same sequence whatever the run seed, as in Isaac Sim).
Rng makeBehaviorRng(int64_t runSeed, std::string_view primPath, std::string_view behavior, uint64_t iteration,
                    int32_t fixedSeed);

}  // namespace sdg
