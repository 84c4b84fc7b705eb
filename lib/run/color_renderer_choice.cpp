#include "run/color_renderer_choice.h"

#include "core/log.h"
#include "render/pathtrace/cpu_tracer_color.h"
#include "render/raster/raster_color.h"
#ifdef SDG_HAVE_GPU_PATHTRACER
#include "render/pathtrace/gpu/gpu_tracer_color.h"
#endif

namespace sdg {
namespace {

// The GPU tracer's factory where its library is built in (see
// render/color_renderer.h, "Adding a renderer"). A flag beside it, not a
// null function pointer: the compiler warns about testing a function's address.
#ifdef SDG_HAVE_GPU_PATHTRACER
constexpr bool kGpuTracerBuiltIn = true;
std::unique_ptr<ColorRenderer> makeGpuTracer(const ColorRendererInputs& inputs) { return makeGpuTracerColor(inputs); }
#else
constexpr bool kGpuTracerBuiltIn = false;
std::unique_ptr<ColorRenderer> makeGpuTracer(const ColorRendererInputs&) { return nullptr; }
#endif

}  // namespace

const char* const kNoGpuTracer =
    "render.pathtracer: gpu, but this build of sdgbehave has no GPU path tracer; use render.pathtracer: cpu (or auto)";

const char* const kGpuTracerNoLens =
    "render.pathtracer: gpu, but a camera has a calibrated lens (omni:lensdistortion:model), which the GPU path "
    "tracer does not follow yet; use render.pathtracer: cpu (or auto)";

bool gpuPathTracerBuiltIn() { return kGpuTracerBuiltIn; }

std::unique_ptr<ColorRenderer> makeColorRenderer(const ColorRendererInputs& inputs, const SourceLoc& setting) {
  const RenderSettings& s = inputs.settings;
  if (s.mode == RenderMode::Raster) return makeRasterColor(inputs);
  switch (s.pathTracer) {
    case PathTracerChoice::Cpu:
      return makeCpuTracerColor(inputs);
    case PathTracerChoice::Gpu:
      if (!kGpuTracerBuiltIn) throw SceneError(setting, kNoGpuTracer);
      if (inputs.calibratedLens) throw SceneError(setting, kGpuTracerNoLens);
      try {
        return makeGpuTracer(inputs);
      } catch (const RendererUnavailable& e) {
        throw RunError(std::string("render.pathtracer: gpu: the GPU path tracer cannot run here: ") + e.what());
      }
    case PathTracerChoice::Auto:
      if (kGpuTracerBuiltIn && !inputs.calibratedLens) {
        try {
          return makeGpuTracer(inputs);
        } catch (const RendererUnavailable& e) {
          log::warn(std::string("render.pathtracer: auto: the GPU path tracer cannot run here (") + e.what() +
                    "); tracing on the CPU");
        }
      }
      return makeCpuTracerColor(inputs);
  }
  return makeCpuTracerColor(inputs);
}

}  // namespace sdg
