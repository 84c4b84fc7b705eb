#pragma once
// The CPU path tracer as a ColorRenderer (render.pathtracer: cpu): the
// tracer, optionally the denoiser, then the rasterizer's tone curve, into
// the frame whose labels the rasterizer drew. Both see the same render list
// and camera, so labels and colour line up pixel for pixel.
#include <memory>

#include "render/color_renderer.h"
#include "render/pathtrace/denoiser.h"
#include "render/pathtrace/path_tracer.h"

namespace sdg {

class CpuTracerColor final : public ColorRenderer {
 public:
  // Traces on inputs.threads cores (0: all).
  explicit CpuTracerColor(const ColorRendererInputs& inputs);

  void render(const RenderList& list, size_t cameraIndex, uint64_t frameSeed, FramePasses& passes,
              bool keepRadiance) override;
  bool replacesRasterColor() const override { return true; }
  bool producesRadiance() const override { return true; }
  std::string device() const override { return "path tracer (CPU, Embree)"; }

  const PathTraceStats& stats() const { return tracer_.stats(); }

 private:
  RenderSettings settings_;
  PathTracer tracer_;
  Denoiser denoiser_;
  PathTracedFrame frame_;
};

std::unique_ptr<ColorRenderer> makeCpuTracerColor(const ColorRendererInputs& inputs);

// Shared with the GPU tracer's ColorRenderer (render/pathtrace/gpu): the
// tracer's and the denoiser's settings from the run's, and what both do with
// their film: the denoiser (render.denoise), the tone curve into
// passes.rgba, the radiance kept for writer.hdr_color.
PathTraceSettings pathTraceSettingsOf(const RenderSettings& settings, int threads);
DenoiseSettings denoiseSettingsOf(int threads);
void finishTracedColor(const RenderSettings& settings, Denoiser& denoiser, PathTracedFrame& frame, FramePasses& passes,
                       bool keepRadiance);

}  // namespace sdg
