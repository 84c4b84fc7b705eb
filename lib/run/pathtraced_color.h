#pragma once
// The path-traced colour of a frame (render.mode: pathtraced): the path
// tracer, optionally the denoiser, then the rasterizer's tone curve, into
// the frame whose labels the rasterizer drew. Both see the same render list
// and camera, so labels and colour line up pixel for pixel.
#include <cstdint>
#include <memory>

#include "assets/asset_resolver.h"
#include "render/frame_passes.h"
#include "render/pathtrace/denoiser.h"
#include "render/pathtrace/path_tracer.h"
#include "render/render_list.h"
#include "render/render_settings.h"

namespace sdg {

class PathTracedColor {
 public:
  // `threads`: the cores to trace with (0: all).
  PathTracedColor(const AssetResolver& assets, const RenderSettings& settings, int threads);

  // Replaces passes.rgba with camera `cameraIndex`'s path-traced colour;
  // with `keepRadiance` also fills passes.hdrColor with its linear radiance.
  void render(const RenderList& list, size_t cameraIndex, uint64_t frameSeed, FramePasses& passes, bool keepRadiance);

  const PathTraceStats& stats() const { return tracer_.stats(); }

 private:
  RenderSettings settings_;
  PathTracer tracer_;
  Denoiser denoiser_;
  PathTracedFrame frame_;
};

// A frame's sample streams: from the run seed, the frame number and the
// render product only, so shards and thread counts agree.
uint64_t pathTraceSeed(int64_t runSeed, uint64_t frame, size_t product);

}  // namespace sdg
