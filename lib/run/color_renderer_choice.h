#pragma once
// Picks the frame's ColorRenderer (render/color_renderer.h) from the
// settings, once per run or picture: render.mode raster -> the rasterizer;
// pathtraced -> render.pathtracer's tracer.
#include <memory>

#include "core/diagnostics.h"
#include "render/color_renderer.h"

namespace sdg {

// `setting`: where render.pathtracer was set, for the error that a choice
// this build or machine cannot honour is (exit 2 when not built in).
// render.pathtracer: gpu without a usable GPU tracer is an error; auto
// falls back to the CPU tracer, with one warning when a GPU tracer is built
// in but cannot run here.
std::unique_ptr<ColorRenderer> makeColorRenderer(const ColorRendererInputs& inputs, const SourceLoc& setting);

// The error for render.pathtracer: gpu in a build without a GPU tracer.
extern const char* const kNoGpuTracer;
// The same for render.pathtracer: gpu with a camera that has a calibrated lens.
extern const char* const kGpuTracerNoLens;

// Whether this build has a GPU path tracer (render.pathtracer: gpu).
bool gpuPathTracerBuiltIn();

}  // namespace sdg
