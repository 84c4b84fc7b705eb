#pragma once
// How frames are drawn, for both modes: the rasterizer (render/raster/) and
// the path tracer (render/pathtrace/).
namespace sdg {

enum class RenderMode { Raster, PathTraced };
// Which path tracer draws render.mode pathtraced (render.pathtracer):
// auto takes the GPU tracer where one is built in and usable, else the CPU's.
enum class PathTracerChoice { Auto, Cpu, Gpu };

// The fields a scene sets (resolution, subframes, mode, pathtracer, samples,
// bounces, denoise) have their defaults in one place, the scene's render option table
// (scene_io/settings_specs.cpp); run/'s renderSettingsFor() and
// defaultRenderSettings() fill them from it. The rest are the renderer's own
// constants.
struct RenderSettings {
  int width = 0;
  int height = 0;
  int subframes = 0;  // jittered colour samples averaged per frame
  // Tone mapping: display = 1 - exp(-radiance * exposureScale), then sRGB.
  // With 0.002 a white Lambert surface lit head-on by a distant light of
  // intensity 4000 maps to about 0.92 (sRGB 246); lamps of 20,000-120,000
  // at a few metres give moderate to bright pools of light.
  float exposureScale = 0.002f;
  // Texels along each side of a light's map (all share one atlas drawn in
  // one pass); 0 picks the output's larger side, which with maps fitted to
  // what the camera sees resolves about one texel per pixel.
  int shadowMapSize = 0;
  // Lights with shadow maps: every distant light and sphere light, up to this
  // many, in stage order; others light without shadows.
  int maxShadowedLights = 4;

  // Colour from the rasterizer or the path tracer (labels always come from
  // the rasterizer's exact passes); the path tracer's inputs.
  RenderMode mode = RenderMode::Raster;
  PathTracerChoice pathTracer = PathTracerChoice::Auto;
  int samples = 0;       // per pixel
  int maxBounces = 0;    // scattering events whose light is counted
  bool denoise = false;  // the edge-aware filter (render/pathtrace/denoiser.h)
  // The GPU every GL context of the process draws on (--gpu): an index among
  // the GPUs it sees (render/egl/egl_devices.h); -1: the first.
  int gpu = -1;

  bool operator==(const RenderSettings&) const = default;
};

}  // namespace sdg
