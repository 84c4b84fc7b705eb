#pragma once
// The GPU path tracer as a ColorRenderer (render.pathtracer: gpu, or auto
// where EGL finds a GPU): the tracer (gpu_path_tracer.h) and optionally the
// denoiser, both on the GPU, then the rasterizer's tone curve, into the
// frame whose labels the rasterizer drew.
#include <memory>

#include "render/color_renderer.h"
#include "render/pathtrace/gpu/gpu_path_tracer.h"

namespace sdg {

class GpuTracerColor final : public ColorRenderer {
 public:
  // RendererUnavailable when the tracer cannot run here.
  explicit GpuTracerColor(const ColorRendererInputs& inputs);

  void render(const RenderList& list, size_t cameraIndex, uint64_t frameSeed, FramePasses& passes,
              bool keepRadiance) override;
  // The tracing, denoising and tone curve run on the device between the two.
  void queue(const RenderList& list, size_t cameraIndex, uint64_t frameSeed, bool keepRadiance, int slot) override;
  void collect(int slot, FramePasses& passes) override;
  bool replacesRasterColor() const override { return true; }
  bool producesRadiance() const override { return true; }
  std::string device() const override;

  const PathTraceStats& stats() const { return tracer_->stats(); }

 private:
  RenderSettings settings_;
  std::unique_ptr<GpuPathTracer> tracer_;
  bool keepRadiance_[2] = {false, false};
};

// Under render.pathtracer: auto, a machine whose EGL has no GPU gets the
// CPU tracer without a warning (llvmpipe would be slower than Embree);
// render.pathtracer: gpu takes llvmpipe too (how CI runs it).
std::unique_ptr<ColorRenderer> makeGpuTracerColor(const ColorRendererInputs& inputs);

}  // namespace sdg
