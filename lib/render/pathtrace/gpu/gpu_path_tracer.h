#pragma once
// sdgbehave's GPU path tracer: the CPU tracer's light transport
// (path_tracer.h) as OpenGL 4.3+ compute shaders, on its own EGL context
// (gl_compute.h): a GPU through EGL's device platform, or Mesa's llvmpipe
// where there is none, so the same kernels are tested in CI.
//
// Same inputs, same film: it takes the render list the CPU tracer takes and
// fills the same PathTracedFrame (radiance, albedo, normal, depth,
// instance), from the same camera rays, sample streams (sampler.h, hashed
// with 64-bit arithmetic in 32-bit words), BSDF, lights, dome importance
// sampling, Russian roulette and next-event estimation with MIS. So both
// converge to the same image; they are not byte-identical to each other
// (the GPU's float rounding, transcendentals and fused multiply-adds differ
// from the CPU's, and its per-pixel sums are float where the CPU's are double).
//
// Geometry: one BVH per distinct mesh (4-wide, gpu_bvh.h), built by
// Embree's builder and uploaded once; a top-level BVH over the instances,
// rebuilt and uploaded only when an instance moved (gpu_scene.h).
//
// Determinism: each pixel is one invocation that adds its samples to its
// own running sum in sample order; nothing is summed across pixels and
// no atomics are used, so a frame is byte-identical run to run on the same
// device and driver, whatever the number of samples per dispatch.
//
// Failure: GpuUnavailable (gl_compute.h) when the device has no GL 4.3
// compute or runs out of memory; RunError, with the driver's log, when a
// kernel does not compile (a bug: exit 1).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "assets/asset_resolver.h"
#include "render/pathtrace/denoiser.h"
#include "render/pathtrace/path_tracer.h"

namespace sdg {

class GpuPathTracer {
 public:
  // Brings up the context and compiles the kernel.
  GpuPathTracer(const AssetResolver& assets, const PathTraceSettings& settings);
  ~GpuPathTracer();
  GpuPathTracer(const GpuPathTracer&) = delete;
  GpuPathTracer& operator=(const GpuPathTracer&) = delete;

  // As PathTracer::render. Callable from any one thread at a time; the GL
  // work runs on the context's own thread (gl_compute.h), so the caller's
  // current context (the rasterizer's) is never touched.
  void render(const RenderList& list, size_t cameraIndex, int width, int height, uint64_t frameSeed,
              PathTracedFrame& out);

  // A run's form, in two steps, so the device traces one frame while the
  // caller works on the previous: queueDisplay() uploads the stage's
  // changes and queues the tracing, the denoiser and the tone curve
  // (path_tracer.h's toneMap(), on the device, within one code value of
  // it) into `slot` (0 or 1), and returns without waiting; collectDisplay()
  // waits for that slot and copies out its RGBA8 frame and, where
  // `radiance` was asked for, the linear radiance (3 floats a pixel). Only
  // these leave the device (1 MB for 512 x 512, not the 16 MB film).
  // `list` may change or go once queueDisplay() returns. stats() is not
  // updated by this form (counting the rays would need the film).
  void queueDisplay(const RenderList& list, size_t cameraIndex, int width, int height, uint64_t frameSeed,
                    float exposureScale, bool radiance, int slot);
  void collectDisplay(int slot, std::vector<uint8_t>& rgba, std::vector<float>* radiance);

  const PathTraceStats& stats() const;
  // With a value, render() also runs the denoiser (denoiser.h's filter,
  // ported to a compute kernel; `threads` is not read) on the GPU before
  // the frame is read back: out.radiance is then the denoised radiance (and
  // out.variance is left 0). perPixelVariance: the filter's SVGF mode on the
  // samples' own variance (DenoiseInputs::variance), else its neighbourhood
  // estimate. Close to the CPU Denoiser's output on the same film, not
  // byte-identical.
  void setDenoiser(const std::optional<DenoiseSettings>& settings, bool perPixelVariance = true);
  // Samples per pixel in one dispatch; 0 (the default): about 4 million
  // paths a dispatch. On a software device (llvmpipe) fewer, whatever is
  // asked (gpu_path_tracer.cpp says why). Changes the timing, never the image.
  void setSamplesPerDispatch(int samples);
  // The tracing kernel is compiled for each frame's stage's features
  // (gpu_scene.h's GpuKernelFeature; the first frame with a new set pays
  // the compilation); with `every`, one kernel holding all of them traces
  // every frame instead. The same image either way, to the GPU's rounding
  // (tests compare them).
  void setEveryKernelFeature(bool every);
  // The GpuKernelFeature bits of the last frame's stage.
  uint32_t stageFeatures() const;
  // The GL renderer and version strings.
  std::string device() const;
  bool onGpu() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sdg
