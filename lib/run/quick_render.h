#pragma once
// One picture of a stage, the one path for `sdgbehave render` (the scene as
// authored: no pre-roll, no behaviors, so a user sees a scene in a second)
// and the studio's previews (the stage at a frame, in one of five passes):
// the camera it is taken from, the renderer kept between pictures, the
// pass overlays, the PNG.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "run/scene_setup.h"

namespace sdg {

class GlContext;
class Renderer;
struct RenderList;

// What a picture shows: the colour image, or it with each labelled pixel
// tinted in its class (semantic) or instance colour, each labelled object's
// tight 2D box outlined in its class colour, or the distance to the image
// plane in grey. Overlays use the `class` labels.
enum class PicturePass { Rgb, Semantic, Instance, Boxes, Depth };
// "rgb", "semantic", "instance", "boxes", "depth", in that order.
const std::vector<std::string>& picturePassNames();
std::optional<PicturePass> picturePassNamed(const std::string& name);

// The camera a picture is taken from: `wanted`, else the first of
// capture.cameras, else the first Camera prim. SceneError when the scene
// has no camera, or (located at `flag`) when `wanted` is not one of them.
size_t pictureCamera(const RenderList& list, const Scene& scene, const std::string& wanted, const std::string& flag);

struct Picture {
  std::vector<uint8_t> png;
  std::string camera;  // its path
  std::string device;  // what drew it: GL_RENDERER via backend, or the path tracer
  int width = 0, height = 0;
};

// Draws pictures of a loaded scene's stages. The GL context and renderer
// are made on the first picture, on the calling thread, and kept for the
// next ones (remade when the scene's render settings or asset roots
// change), so call it from one thread.
class PictureRenderer {
 public:
  // With `rasterOnly` colour always comes from the rasterizer (the studio:
  // a preview takes milliseconds, a path-traced frame seconds); otherwise
  // render.mode decides, and a path-traced picture is rgb only.
  PictureRenderer(RenderOverrides overrides, bool rasterOnly);
  ~PictureRenderer();
  PictureRenderer(const PictureRenderer&) = delete;
  PictureRenderer& operator=(const PictureRenderer&) = delete;

  // `stage` is `loaded`'s stage or one derived from it (after a pre-roll
  // and some updates); `camera` as for pictureCamera(), named `flag` in
  // messages.
  Picture render(const LoadedScene& loaded, const Stage& stage, const std::string& camera, const std::string& flag,
                 PicturePass pass);

 private:
  Renderer& rasterizer(const LoadedScene& loaded, const RenderSettings& settings);

  RenderOverrides overrides_;
  bool rasterOnly_;
  std::unique_ptr<GlContext> context_;
  std::unique_ptr<Renderer> renderer_;
  // What renderer_ was made with (it keeps a reference to the resolver).
  std::unique_ptr<AssetResolver> assets_;
  std::optional<RenderSettings> settings_;
};

// `sdgbehave render`: one rgb picture of the scene as authored, written
// atomically as a PNG.
struct QuickRenderOptions {
  std::string camera;  // "" = the first of capture.cameras, else the first Camera
  std::string outputPath;
  RenderOverrides render;
};

struct QuickRenderResult {
  std::string camera;
  std::string renderer;  // GL_RENDERER via backend, or the path tracer
  int width = 0, height = 0;
};

QuickRenderResult renderOnePicture(const LoadedScene& loaded, const QuickRenderOptions& options);

}  // namespace sdg
