#pragma once
// The one interface behind which a frame's colour is made: the rasterizer,
// the CPU path tracer, the GPU path tracer. A run or a picture picks one
// from its RenderSettings, once (run/color_renderer_choice.h), and calls it
// for every render product; nothing downstream asks which one it got.
//
// Labels (ids, depth, normals, coverage) always come from the rasterizer's
// exact passes, drawn before render() is called; a renderer only replaces
// the colour (passes.rgba) and, where it has one, the linear radiance
// (passes.hdrColor). The rasterizer's colour is drawn with its labels, so
// its ColorRenderer keeps passes.rgba as drawn.
//
// Adding a renderer (e.g. the GPU path tracer):
// 1. Derive from ColorRenderer in its own files under render/<kind>/
//    (path tracers under render/pathtrace/), in its own library target in
//    lib/CMakeLists.txt; only a renderer that needs GL links the GL library.
// 2. Give it a factory `std::unique_ptr<ColorRenderer> makeX(const
//    ColorRendererInputs&)` that throws RendererUnavailable when it cannot
//    run here (no GPU, missing compute features, out of memory): under
//    render.pathtracer: auto the choice then falls back to the CPU tracer
//    with one warning, under an explicit choice it is the run's error.
// 3. Enter the factory in run/color_renderer_choice.cpp's table (for the GPU
//    tracer: the slot guarded by SDG_HAVE_GPU_PATHTRACER, which its library
//    target defines PUBLIC), and link its library into sdg_run.
// 4. Every setting it reads comes from RenderSettings, whose defaults are in
//    the scene's render option table (scene_io/settings_specs.cpp) only.
// 5. Derive its sample streams from frameSampleSeed() below, so every
//    renderer of a run sees the same seed for the same product and frame.
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

#include "render/frame_passes.h"
#include "render/render_list.h"
#include "render/render_settings.h"

namespace sdg {

class AssetResolver;
class GlContext;  // render/raster/gl_context.h; only GL renderers use it

// What a renderer may use, given once when it is made.
struct ColorRendererInputs {
  const AssetResolver& assets;
  RenderSettings settings;
  int threads = 0;  // CPU cores to use; 0: all
  // The rasterizer's GL context, current on the thread that calls render()
  // from the first call on (made on demand where the caller has none yet).
  // Unset where no GL context may be made.
  std::function<GlContext&()> glContext;
  // Some camera has a calibrated lens (RenderCamera::lens), which the GPU
  // path tracer does not follow yet: render.pathtracer auto then traces on
  // the CPU, and gpu is refused.
  bool calibratedLens = false;
};

// Thrown by a factory whose renderer cannot run on this machine; the text
// says why, for the warning or the error the choice turns it into.
class RendererUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ColorRenderer {
 public:
  virtual ~ColorRenderer() = default;

  // Makes camera `cameraIndex`'s colour of `list` in passes.rgba (sized
  // settings.width x settings.height); with `keepRadiance` also its linear
  // radiance in passes.hdrColor (only where producesRadiance()). frameSeed
  // keys the sample streams (frameSampleSeed()). Throws RunError for what
  // the scene's files cannot give (a mesh, a texture).
  virtual void render(const RenderList& list, size_t cameraIndex, uint64_t frameSeed, FramePasses& passes,
                      bool keepRadiance) = 0;

  // The two-step form of render(), for a caller that works on one product
  // while the next is made (a run): queue() starts a product's colour in
  // slot 0 or 1, collect() finishes it into passes. `list` must stay alive
  // and unchanged until the slot is collected. By default queue() keeps the
  // arguments and collect() calls render(); a renderer that works
  // asynchronously (the GPU tracer) overrides both.
  virtual void queue(const RenderList& list, size_t cameraIndex, uint64_t frameSeed, bool keepRadiance, int slot);
  virtual void collect(int slot, FramePasses& passes);

  // false: the colour is the rasterizer's own pass, drawn with the labels
  // (render() leaves it); true: render() makes it without the rasterizer,
  // so a colour-only picture needs no GL context for it.
  virtual bool replacesRasterColor() const = 0;
  // Whether render() can fill passes.hdrColor (writer.hdr_color).
  virtual bool producesRadiance() const = 0;
  // Shown as the picture's device; empty: the GL context's name tells it.
  virtual std::string device() const = 0;

 private:
  struct Queued {
    const RenderList* list = nullptr;
    size_t cameraIndex = 0;
    uint64_t frameSeed = 0;
    bool keepRadiance = false;
  };
  Queued queued_[2];
};

// A frame's sample streams: from the run seed, the frame number and the
// render product only, so shards, thread counts and renderers agree.
uint64_t frameSampleSeed(int64_t runSeed, uint64_t frame, size_t product);

}  // namespace sdg
