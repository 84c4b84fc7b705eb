#include "render/color_renderer.h"

namespace sdg {
namespace {

uint64_t mix(uint64_t x) {  // splitmix64's finaliser
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

}  // namespace

uint64_t frameSampleSeed(int64_t runSeed, uint64_t frame, size_t product) {
  return mix(mix(uint64_t(runSeed) ^ 0x70617468ull) ^ mix(frame + 1) ^ mix(uint64_t(product) << 32));
}

}  // namespace sdg
