#include "render/color_renderer.h"

#include <stdexcept>
#include <string>

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

void ColorRenderer::queue(const RenderList& list, size_t cameraIndex, uint64_t frameSeed, bool keepRadiance, int slot) {
  if (slot < 0 || slot > 1) throw std::invalid_argument("ColorRenderer: no slot " + std::to_string(slot));
  queued_[slot] = Queued{&list, cameraIndex, frameSeed, keepRadiance};
}

void ColorRenderer::collect(int slot, FramePasses& passes) {
  if (slot < 0 || slot > 1 || !queued_[slot].list)
    throw std::logic_error("ColorRenderer: nothing queued in slot " + std::to_string(slot));
  const Queued q = queued_[slot];
  queued_[slot] = Queued{};
  render(*q.list, q.cameraIndex, q.frameSeed, passes, q.keepRadiance);
}

}  // namespace sdg
