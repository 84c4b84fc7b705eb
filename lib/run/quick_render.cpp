#include "run/quick_render.h"

#include "core/diagnostics.h"
#include "core/file_io.h"
#include "core/text.h"
#include "render/raster/renderer.h"
#include "run/pathtraced_color.h"
#include "writers/png_encoder.h"

namespace sdg {

QuickRenderResult renderOnePicture(const LoadedScene& loaded, const QuickRenderOptions& options) {
  const Scene& scene = loaded.scene;
  RenderList list = buildRenderList(scene.stage);
  std::string wanted = options.camera;
  if (wanted.empty()) {
    const auto& cameras = scene.capture.get("cameras").get<std::vector<std::string>>();
    if (!cameras.empty()) wanted = cameras.front();
  }
  size_t index = 0;
  if (list.cameras.empty()) throw SceneError(SourceLoc{scene.sourcePath, 0, 0}, "the scene has no Camera prim to render from");
  if (!wanted.empty()) {
    std::vector<std::string> names;
    index = list.cameras.size();
    for (size_t i = 0; i < list.cameras.size(); ++i) {
      names.push_back(list.cameras[i].path);
      if (list.cameras[i].path == wanted) index = i;
    }
    if (index == list.cameras.size())
      throw SceneError(SourceLoc{"--camera", 0, 0}, text::quote(wanted) + " is not a Camera of the scene; cameras: " +
                                                        text::join(names, ", ") + text::didYouMean(wanted, names));
  }
  const RenderSettings settings = renderSettingsFor(scene, options.render);
  FramePasses frame;
  std::string device;
  if (settings.mode == RenderMode::PathTraced) {
    // The picture is the path tracer's alone: no GL context is made.
    frame.resize(settings.width, settings.height, PassSelection::colourOnly());
    PathTracedColor(loaded.assets, settings, 0).render(list, index, pathTraceSeed(0, 0, index), frame, false);
    device = "path tracer (CPU, Embree)";
  } else {
    std::unique_ptr<GlContext> context = glContextFor(scene, options.render);
    Renderer renderer(*context, loaded.assets, settings);
    renderer.render(list, index, frame, PassSelection::colourOnly());
    device = context->rendererName() + " via " + context->backend();
  }
  std::vector<uint8_t> png = encodePng(frame.rgba, uint32_t(frame.width), uint32_t(frame.height), PngPixels::Rgba8,
                                        PngOptions::renderedImage());
  writeFileAtomic(options.outputPath, png);
  return QuickRenderResult{list.cameras[index].path, device, frame.width, frame.height};
}

}  // namespace sdg
