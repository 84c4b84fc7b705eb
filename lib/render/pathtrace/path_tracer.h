#pragma once
// sdgbehave's CPU path tracer: the render list traced with Intel Embree 3.
//
// Light transport: unidirectional path tracing with next-event estimation
// at every vertex and multiple importance sampling (the power heuristic)
// between light sampling and BSDF sampling for every light that has an
// area or a solid angle (pbrt-v4's PathIntegrator, Veach 1997 ch. 9);
// Russian roulette from the fourth vertex on. Surfaces are PbrBsdf
// (bsdf.h) with the rasterizer's material inputs (pt_materials.h); lights
// are pt_lights.h's, with the rasterizer's radiometry.
//
// The camera is the rasterizer's (render/camera_math.h): pixel (x, y)
// covers [x, x + 1) x [y, y + 1) of the image, y down; each sample's
// primary ray goes through a point drawn uniformly in that square (a box
// filter), from the near clipping plane to the far one, perspective or
// orthographic; a calibrated lens (render/lens_model.h) unprojects the
// point instead, the ray leaving the eye (docs/rendering.md, "Lens
// models"). The labels-like planes (albedo, normal, depth, instance)
// come from one extra ray through the pixel's centre, the rasterizer's
// unjittered ray, so they line up with its labels exactly; light shapes do
// not appear in them.
//
// Traversal: wavefront tiles. A thread takes a 16 x 16 tile and traces one
// sample of each of its pixels together, depth by depth: the tile's live
// paths' rays go through one Embree ray stream (camera rays as coherent
// packets), each vertex is shaded and queues its shadow ray, and the shadow
// rays go through another stream. Against one rtcIntersect1 call a ray this
// saves Embree's per-call cost and lets it trace nearby rays as packets.
//
// Determinism: a pixel's value depends only on the scene, the settings,
// frameSeed, the pixel (render/pathtrace/sampler.h's streams, its own sum
// in sample order) and possibly the rays traced beside it in its tile's
// streams (Embree's stream traversal does not promise a ray the hit it
// would get alone, to the last bit): tiles are handed to
// threads from an atomic counter, but a tile's streams are its own paths in
// pixel order and no value is ever summed across pixels or threads, so the
// radiance is byte-identical whatever `threads` is. Embree's BVHs are built
// on one thread (embree_scene.h).
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "assets/asset_resolver.h"
#include "render/pathtrace/embree_scene.h"
#include "render/render_list.h"

namespace sdg {

// A run fills these from its RenderSettings (whose defaults are the scene's
// render option table); the tracer itself assumes none.
struct PathTraceSettings {
  int samples = 0;     // per pixel
  int maxBounces = 0;  // path length limit (Russian roulette after 3): the scattering events whose light is counted
  int threads = 0;     // 0: hardware concurrency
  int gpu = -1;        // the GPU tracer's device among the visible GPUs (--gpu); -1: the first
};

struct PathTracedFrame {  // rows top to bottom, like FramePasses
  int width = 0, height = 0;
  std::vector<float> radiance;     // linear RGB, 3 per pixel
  std::vector<float> albedo;       // first-hit base colour (RGB), for the denoiser
  std::vector<float> normal;       // first-hit shading normal (xyz), facing the camera; 0 for background
  std::vector<float> depth;        // first-hit distance from the camera's position, scene units; +inf for background
  std::vector<uint32_t> instance;  // first-hit RenderItem::instanceId; 0 background
  // Per pixel: the variance of the radiance's mean luminance (the samples'
  // variance over their count), the denoiser's per-pixel noise estimate.
  std::vector<float> variance;
};

// What the last render() did, for benchmarks.
struct PathTraceStats {
  uint64_t rays = 0;         // closest-hit and shadow rays traced through Embree
  uint64_t cameraRays = 0;   // of which primary rays (the samples' and the label rays)
  uint64_t samples = 0;
  uint64_t droppedSamples = 0;  // not finite: left out of their pixel's mean
  double seconds = 0;        // the tracing itself, threads running
  double setupSeconds = 0;   // meshes, textures, the frame's scene
  int threads = 0;
};

// Benchmarks: the rays a render() cast, so that Embree alone can cast the
// very same rays again (PathTracer::replayRate).
enum class TracedRayKind : uint8_t { Camera, Bounce, Shadow };
struct TracedRay {
  PtRay ray;
  TracedRayKind kind;
};
struct RayLog {
  std::vector<std::vector<TracedRay>> perThread;  // each thread's rays in the order it cast them
};

struct PtWaveBuffers;  // path_tracer.cpp: a thread's paths and ray streams, kept from frame to frame
struct PtFrameData;  // path_tracer.cpp: what one render() reads while its threads run

class PathTracer {
 public:
  PathTracer(const AssetResolver& assets, const PathTraceSettings& settings);
  ~PathTracer();
  PathTracer(const PathTracer&) = delete;
  PathTracer& operator=(const PathTracer&) = delete;

  // Renders camera `cameraIndex` of `list` at width x height. frameSeed keys every pixel's sample stream.
  // Meshes and textures are loaded once and cached; the Embree scene is rebuilt from the list each call
  // but each distinct mesh's BLAS is built once and instanced (so a moving object is a new transform, not a rebuild).
  // Throws RunError for a mesh, texture or dome map that cannot be read, and std::invalid_argument for
  // a camera index out of range or a size below 1. One render at a time per PathTracer (it owns the caches).
  // A RenderItem's doubleSided is not read: every face is seen from both sides, as in the rasterizer.
  void render(const RenderList& list, size_t cameraIndex, int width, int height, uint64_t frameSeed,
              PathTracedFrame& out);

  const PathTraceStats& stats() const { return stats_; }

  // The rate of plain Embree ray casting on the same frame scene: each
  // pixel's centre ray, closest hit only, no shading (rays per second over
  // all threads). For comparison with stats(); renders nothing.
  double primaryRayRate(const RenderList& list, size_t cameraIndex, int width, int height, int repeats = 4);

  // Benchmarks: while `log` is set (null: not), render() records every ray
  // it casts into it.
  void recordRays(RayLog* log) { rayLog_ = log; }
  // Plain Embree ray casting of a RayLog's rays on the same frame scene (the
  // list render() recorded it from), no shading: rays per second over all
  // threads, each thread casting the rays it cast in the render. With
  // `streams`, every 1,024 rays of a thread are cast by kind through
  // EmbreeScene's streams (camera rays as coherent packets); else one
  // rtcIntersect1 / rtcOccluded1 call per ray, as recorded.
  double replayRate(const RenderList& list, const RayLog& log, bool streams, int repeats = 4);

 private:
  struct Caches;
  void prepare(const RenderList& list, PtFrameData& frame);

  const AssetResolver& assets_;
  PathTraceSettings settings_;
  std::unique_ptr<Caches> caches_;
  PathTraceStats stats_;
  RayLog* rayLog_ = nullptr;
  std::vector<std::unique_ptr<PtWaveBuffers>> waves_;  // per thread
};

// The rasterizer's tone curve (display = 1 - exp(-radiance * exposureScale), then sRGB, rounded) into RGBA8, alpha 255.
void toneMap(const PathTracedFrame& frame, float exposureScale, uint8_t* rgba);

}  // namespace sdg
