#include "render/pathtrace/gpu/gpu_tracer_color.h"

#include "core/diagnostics.h"
#include "render/pathtrace/cpu_tracer_color.h"
#include "render/pathtrace/gpu/gl_compute.h"

namespace sdg {
namespace {

std::unique_ptr<GpuPathTracer> makeTracer(const ColorRendererInputs& inputs) {
  try {
    return std::make_unique<GpuPathTracer>(inputs.assets, pathTraceSettingsOf(inputs.settings, inputs.threads));
  } catch (const GpuUnavailable& e) {
    throw RendererUnavailable(e.what());
  }
}

}  // namespace

GpuTracerColor::GpuTracerColor(const ColorRendererInputs& inputs)
    : settings_(inputs.settings), tracer_(makeTracer(inputs)) {
  if (settings_.denoise) tracer_->setDenoiser(denoiseSettingsOf(inputs.threads));
}

std::string GpuTracerColor::device() const { return "path tracer (GPU: " + tracer_->device() + ")"; }

void GpuTracerColor::render(const RenderList& list, size_t cameraIndex, uint64_t frameSeed, FramePasses& passes,
                            bool keepRadiance) {
  queue(list, cameraIndex, frameSeed, keepRadiance, 0);
  collect(0, passes);
}

void GpuTracerColor::queue(const RenderList& list, size_t cameraIndex, uint64_t frameSeed, bool keepRadiance, int slot) {
  try {
    tracer_->queueDisplay(list, cameraIndex, settings_.width, settings_.height, frameSeed, settings_.exposureScale,
                          keepRadiance, slot);
  } catch (const GpuUnavailable& e) {
    // Out of memory mid-run: the frames so far came from the GPU, so falling
    // back now would mix two tracers in one dataset; the run stops instead.
    throw RunError(std::string(e.what()) + " (use render.pathtracer: cpu for this scene)");
  }
  keepRadiance_[slot] = keepRadiance;
}

void GpuTracerColor::collect(int slot, FramePasses& passes) {
  tracer_->collectDisplay(slot, passes.rgba, keepRadiance_[slot] ? &passes.hdrColor : nullptr);
}

std::unique_ptr<ColorRenderer> makeGpuTracerColor(const ColorRendererInputs& inputs) {
  if (inputs.settings.pathTracer == PathTracerChoice::Auto && !eglGpuDeviceListed()) return makeCpuTracerColor(inputs);
  return std::make_unique<GpuTracerColor>(inputs);
}

}  // namespace sdg
