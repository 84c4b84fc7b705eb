#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "behavior/rng.h"

using namespace sdg;

TEST_CASE("rng: PCG32 matches the reference generator's published output", "[behavior][rng]") {
  // pcg32_srandom_r(42, 54) from the PCG reference implementation's demo.
  Rng rng(42, 54);
  const uint32_t expected[] = {0xa15c02b7, 0x7b47f409, 0xba1d3330, 0x83d2f293, 0xbfa4784b, 0xcbed606e};
  for (uint32_t e : expected) CHECK(rng.nextU32() == e);
}

TEST_CASE("rng: uniform draws stay in range with the right mean", "[behavior][rng]") {
  Rng rng(7, 1);
  const int n = 10000;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    double u = rng.uniform(-2.0, 3.0);
    REQUIRE(u >= -2.0);
    REQUIRE(u < 3.0);
    sum += u;
  }
  // Uniform on [-2, 3): mean 0.5, sigma 5/sqrt(12); the sample mean within 4 sigma/sqrt(n).
  CHECK(std::fabs(sum / n - 0.5) < 4 * (5 / std::sqrt(12.0)) / std::sqrt(double(n)));
}

TEST_CASE("rng: integers cover the range evenly and never leave it", "[behavior][rng]") {
  Rng rng(3, 9);
  std::vector<int> counts(5, 0);
  const int n = 50000;
  for (int i = 0; i < n; ++i) {
    int64_t v = rng.integers(2, 7);
    REQUIRE(v >= 2);
    REQUIRE(v < 7);
    ++counts[static_cast<size_t>(v - 2)];
  }
  // Binomial(n, 1/5): within 5 sigma of n/5.
  double sigma = std::sqrt(n * 0.2 * 0.8);
  for (int c : counts) CHECK(std::fabs(c - n * 0.2) < 5 * sigma);
}

TEST_CASE("rng: behavior streams depend on seed, prim, namespace and iteration", "[behavior][rng]") {
  auto first = [](Rng r) { return r.nextU32(); };
  uint32_t base = first(makeBehaviorRng(10, "/A", "locationRandomizer", 0, -1));
  CHECK(base == first(makeBehaviorRng(10, "/A", "locationRandomizer", 0, -1)));
  CHECK(base != first(makeBehaviorRng(11, "/A", "locationRandomizer", 0, -1)));
  CHECK(base != first(makeBehaviorRng(10, "/B", "locationRandomizer", 0, -1)));
  CHECK(base != first(makeBehaviorRng(10, "/A", "rotationRandomizer", 0, -1)));
  CHECK(base != first(makeBehaviorRng(10, "/A", "locationRandomizer", 1, -1)));
  // A fixed seed ignores the run seed and the prim.
  CHECK(first(makeBehaviorRng(10, "/A", "x", 0, 5)) == first(makeBehaviorRng(99, "/B", "x", 3, 5)));
}
