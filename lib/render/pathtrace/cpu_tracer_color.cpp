#include "render/pathtrace/cpu_tracer_color.h"

namespace sdg {
namespace {

PathTraceSettings tracerSettings(const RenderSettings& s, int threads) {
  PathTraceSettings p;
  p.samples = s.samples;
  p.maxBounces = s.maxBounces;
  p.threads = threads;
  return p;
}

DenoiseSettings denoiseSettings(int threads) {
  DenoiseSettings d;
  d.threads = unsigned(threads);
  return d;
}

}  // namespace

CpuTracerColor::CpuTracerColor(const ColorRendererInputs& inputs)
    : settings_(inputs.settings),
      tracer_(inputs.assets, tracerSettings(inputs.settings, inputs.threads)),
      denoiser_(denoiseSettings(inputs.threads)) {}

void CpuTracerColor::render(const RenderList& list, size_t cameraIndex, uint64_t frameSeed, FramePasses& passes,
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

std::unique_ptr<ColorRenderer> makeCpuTracerColor(const ColorRendererInputs& inputs) {
  return std::make_unique<CpuTracerColor>(inputs);
}

}  // namespace sdg
