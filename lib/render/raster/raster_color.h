#pragma once
// The rasterizer as a ColorRenderer (render.mode: raster): its colour is
// drawn in the same pass as the labels (Renderer::queue/render), so there
// is nothing left to make; render() keeps passes.rgba as drawn.
#include <memory>

#include "render/color_renderer.h"

namespace sdg {

class RasterColor final : public ColorRenderer {
 public:
  void render(const RenderList&, size_t, uint64_t, FramePasses&, bool) override {}
  bool replacesRasterColor() const override { return false; }
  bool producesRadiance() const override { return false; }
  std::string device() const override { return ""; }
};

inline std::unique_ptr<ColorRenderer> makeRasterColor(const ColorRendererInputs&) {
  return std::make_unique<RasterColor>();
}

}  // namespace sdg
