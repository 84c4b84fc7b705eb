#include "run/quick_render.h"

#include <algorithm>
#include <climits>

#include "core/diagnostics.h"
#include "core/file_io.h"
#include "core/text.h"
#include "render/raster/renderer.h"
#include "render/render_list.h"
#include "run/color_renderer_choice.h"
#include "writers/colors.h"
#include "writers/png_encoder.h"
#include "writers/semantics.h"

namespace sdg {
namespace {

// Blends `color` over the pixel at `i` (rgba), by `alpha` in [0, 1].
void blend(std::vector<uint8_t>& rgba, size_t i, const std::array<uint8_t, 4>& color, float alpha) {
  for (size_t c = 0; c < 3; ++c) rgba[4 * i + c] = uint8_t(float(rgba[4 * i + c]) * (1 - alpha) + float(color[c]) * alpha);
}

// The pass drawn over the colour of `frame` (rendered with every pass).
void overlay(std::vector<uint8_t>& rgba, const FramePasses& frame, const Stage& stage, const RenderList& list,
             PicturePass pass) {
  const size_t pixels = frame.pixelCount();
  if (pass == PicturePass::Depth) {
    const std::vector<uint8_t> grey = colorizeDistance(frame.distanceToImagePlane);
    for (size_t i = 0; i < pixels; ++i) rgba[4 * i] = rgba[4 * i + 1] = rgba[4 * i + 2] = grey[i];
    return;
  }
  const FrameSemantics semantics = computeSemantics(stage, list, {"class"});
  struct Box {
    int x0 = INT_MAX, y0 = INT_MAX, x1 = -1, y1 = -1;
  };
  std::vector<Box> boxes(semantics.entities.size());
  for (size_t i = 0; i < pixels; ++i) {
    const uint32_t id = frame.instanceIds[i];
    const uint32_t entity = id < semantics.entityOfRenderId.size() ? semantics.entityOfRenderId[id] : 0;
    if (entity == 0) continue;
    const SemanticEntity& e = semantics.entities[entity - 1];
    if (pass == PicturePass::Semantic) blend(rgba, i, idColor(e.semanticId), 0.6f);
    if (pass == PicturePass::Instance) blend(rgba, i, idColor(e.instanceId), 0.6f);
    Box& b = boxes[entity - 1];
    const int x = int(i % size_t(frame.width)), y = int(i / size_t(frame.width));
    b.x0 = std::min(b.x0, x), b.y0 = std::min(b.y0, y), b.x1 = std::max(b.x1, x), b.y1 = std::max(b.y1, y);
  }
  if (pass != PicturePass::Boxes) return;
  for (size_t e = 0; e < boxes.size(); ++e) {
    const Box& b = boxes[e];
    if (b.x1 < 0) continue;
    const auto color = idColor(semantics.entities[e].semanticId);
    auto paint = [&](int x, int y) { blend(rgba, size_t(y) * size_t(frame.width) + size_t(x), color, 1.0f); };
    for (int x = b.x0; x <= b.x1; ++x) paint(x, b.y0), paint(x, b.y1);
    for (int y = b.y0; y <= b.y1; ++y) paint(b.x0, y), paint(b.x1, y);
  }
}

}  // namespace

const std::vector<std::string>& picturePassNames() {
  static const std::vector<std::string> kNames = {"rgb", "semantic", "instance", "boxes", "depth"};
  return kNames;
}

std::optional<PicturePass> picturePassNamed(const std::string& name) {
  const auto& names = picturePassNames();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) return std::nullopt;
  return PicturePass(it - names.begin());
}

size_t pictureCamera(const RenderList& list, const Scene& scene, const std::string& wanted, const std::string& flag) {
  if (list.cameras.empty()) throw SceneError(SourceLoc{scene.sourcePath, 0, 0}, "the scene has no Camera prim to render from");
  std::string name = wanted;
  if (name.empty()) {
    const auto& cameras = scene.capture.get("cameras").get<std::vector<std::string>>();
    if (cameras.empty()) return 0;
    name = cameras.front();
  }
  std::vector<std::string> names;
  for (size_t i = 0; i < list.cameras.size(); ++i) {
    if (list.cameras[i].path == name) return i;
    names.push_back(list.cameras[i].path);
  }
  throw SceneError(SourceLoc{flag, 0, 0}, text::quote(name) + " is not a Camera of the scene; cameras: " +
                                              text::join(names, ", ") + text::didYouMean(name, names));
}

PictureRenderer::PictureRenderer(RenderOverrides overrides, bool rasterOnly)
    : overrides_(std::move(overrides)), rasterOnly_(rasterOnly) {}

PictureRenderer::~PictureRenderer() = default;

Renderer& PictureRenderer::rasterizer(const LoadedScene& loaded, const RenderSettings& settings) {
  if (!context_) context_ = glContextFor(loaded.scene, overrides_);
  const bool sameAssets = assets_ && assets_->roots() == loaded.assets.roots() &&
                          assets_->isaacRoot() == loaded.assets.isaacRoot() &&
                          assets_->confined() == loaded.assets.confined();
  if (renderer_ && sameAssets && settings_ == settings) return *renderer_;
  renderer_.reset();
  assets_ = std::make_unique<AssetResolver>(loaded.assets);
  settings_ = settings;
  renderer_ = std::make_unique<Renderer>(*context_, *assets_, settings);
  return *renderer_;
}

Picture PictureRenderer::render(const LoadedScene& loaded, const Stage& stage, const std::string& camera,
                                const std::string& flag, PicturePass pass) {
  const RenderList list = buildRenderList(stage);
  Picture picture;
  const size_t index = pictureCamera(list, loaded.scene, camera, flag);
  picture.camera = list.cameras[index].path;
  RenderSettings settings = renderSettingsFor(loaded.scene, overrides_);
  if (rasterOnly_) settings.mode = RenderMode::Raster;
  FramePasses frame;
  const SourceLoc* tracerAt = loaded.scene.render.locOf("pathtracer");
  const auto color = makeColorRenderer(
      {loaded.assets, settings, 0,
       [this, &loaded]() -> GlContext& {
         if (!context_) context_ = glContextFor(loaded.scene, overrides_);
         return *context_;
       },
       anyCalibratedLens(list)},
      tracerAt ? *tracerAt : SourceLoc{loaded.scene.sourcePath, 0, 0});
  if (color->replacesRasterColor()) {
    // A traced picture alone: no rasterizer is made for it.
    if (pass != PicturePass::Rgb) throw RunError("a path-traced picture is rgb only");
    frame.resize(settings.width, settings.height, PassSelection::colourOnly());
  } else {
    rasterizer(loaded, settings).render(list, index, frame, pass == PicturePass::Rgb ? PassSelection::colourOnly()
                                                                                     : PassSelection{});
  }
  color->render(list, index, frameSampleSeed(0, 0, index), frame, false);
  picture.device = color->device().empty() ? context_->rendererName() + " via " + context_->backend() : color->device();
  std::vector<uint8_t> rgba = frame.rgba;
  if (pass != PicturePass::Rgb) overlay(rgba, frame, stage, list, pass);
  picture.png = encodePng(rgba, uint32_t(frame.width), uint32_t(frame.height), PngPixels::Rgba8,
                          PngOptions::renderedImage());
  picture.width = frame.width;
  picture.height = frame.height;
  return picture;
}

QuickRenderResult renderOnePicture(const LoadedScene& loaded, const QuickRenderOptions& options) {
  PictureRenderer renderer(options.render, false);
  Picture picture = renderer.render(loaded, loaded.scene.stage, options.camera, "--camera", PicturePass::Rgb);
  writeFileAtomic(options.outputPath, picture.png);
  return QuickRenderResult{picture.camera, picture.device, picture.width, picture.height};
}

}  // namespace sdg
