#include "run/pathtraced_color.h"

namespace sdg {
namespace {

uint64_t mix(uint64_t x) {  // splitmix64's finaliser
  x ^= x >> 30;
  x *= 0xbf58476d1ce4e5b9ull;
  x ^= x >> 27;
  x *= 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

PathTraceSettings tracerSettings(const RenderSettings& s, int threads) {
  PathTraceSettings p;
  p.samples = s.samples;
  p.maxBounces = s.maxBounces;
  p.threads = threads;
  return p;
}

DenoiseSettings denoiseSettings(int threads) {
  DenoiseSettings d;
  d.threads = threads;
  return d;
}

}  // namespace

PathTracedColor::PathTracedColor(const AssetResolver& assets, const RenderSettings& settings, int threads)
    : settings_(settings), tracer_(assets, tracerSettings(settings, threads)), denoiser_(denoiseSettings(threads)) {}

void PathTracedColor::render(const RenderList& list, size_t cameraIndex, uint64_t frameSeed, FramePasses& passes,
                             bool keepRadiance) {
  tracer_.render(list, cameraIndex, settings_.width, settings_.height, frameSeed, frame_);
  if (settings_.denoise) {
    const DenoiseInputs in{frame_.width, frame_.height, frame_.radiance.data(), frame_.albedo.data(),
                           frame_.normal.data(), frame_.depth.data(), frame_.instance.data()};
    denoiser_.run(in, frame_.radiance.data());
  }
  passes.rgba.resize(size_t(frame_.width) * size_t(frame_.height) * 4);
  toneMap(frame_, settings_.exposureScale, passes.rgba.data());
  if (keepRadiance) passes.hdrColor = frame_.radiance;
}

uint64_t pathTraceSeed(int64_t runSeed, uint64_t frame, size_t product) {
  return mix(mix(uint64_t(runSeed) ^ 0x70617468ull) ^ mix(frame + 1) ^ mix(uint64_t(product) << 32));
}

}  // namespace sdg
