#include "render/pathtrace/cpu_tracer_color.h"

namespace sdg {

PathTraceSettings pathTraceSettingsOf(const RenderSettings& s, int threads) {
  PathTraceSettings p;
  p.samples = s.samples;
  p.maxBounces = s.maxBounces;
  p.threads = threads;
  p.gpu = s.gpu;
  return p;
}

DenoiseSettings denoiseSettingsOf(int threads) {
  DenoiseSettings d;
  d.threads = unsigned(threads);
  return d;
}

void finishTracedColor(const RenderSettings& settings, Denoiser& denoiser, PathTracedFrame& frame, FramePasses& passes,
                       bool keepRadiance) {
  if (settings.denoise) {
    const DenoiseInputs in{frame.width, frame.height, frame.radiance.data(), frame.albedo.data(),
                           frame.normal.data(), frame.depth.data(), frame.instance.data(),
                           frame.variance.empty() ? nullptr : frame.variance.data()};
    denoiser.run(in, frame.radiance.data());
  }
  passes.rgba.resize(size_t(frame.width) * size_t(frame.height) * 4);
  toneMap(frame, settings.exposureScale, passes.rgba.data());
  if (keepRadiance) passes.hdrColor = frame.radiance;
}

CpuTracerColor::CpuTracerColor(const ColorRendererInputs& inputs)
    : settings_(inputs.settings),
      tracer_(inputs.assets, pathTraceSettingsOf(inputs.settings, inputs.threads)),
      denoiser_(denoiseSettingsOf(inputs.threads)) {}

void CpuTracerColor::render(const RenderList& list, size_t cameraIndex, uint64_t frameSeed, FramePasses& passes,
                            bool keepRadiance) {
  tracer_.render(list, cameraIndex, settings_.width, settings_.height, frameSeed, frame_);
  finishTracedColor(settings_, denoiser_, frame_, passes, keepRadiance);
}

std::unique_ptr<ColorRenderer> makeCpuTracerColor(const ColorRendererInputs& inputs) {
  return std::make_unique<CpuTracerColor>(inputs);
}

}  // namespace sdg
