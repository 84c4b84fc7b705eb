#pragma once
// Renders inline YAML scenes with the real OSMesa back end.
#include <catch2/catch.hpp>

#include <memory>

#include "assets/asset_resolver.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "render/raster/renderer.h"
#include "scene_io/scene_loader.h"

namespace sdg::test {

// One context for the whole test binary: creating llvmpipe contexts is slow.
inline GlContext& sharedContext() {
  static std::unique_ptr<GlContext> context = createOsMesaContext();
  return *context;
}

struct RenderedScene {
  Scene scene;
  RenderList list;
  FramePasses frame;
};

inline RenderedScene renderYaml(const std::string& yaml, RenderSettings settings = {}) {
  RenderedScene r;
  r.scene = buildScene(sceneDocumentFromText(yaml, "t.yaml"), builtinRegistry().catalog());
  r.list = buildRenderList(r.scene.stage);
  static const AssetResolver assets({SDG_SOURCE_DIR "/scenes", SDG_SOURCE_DIR "/tests/data"});
  Renderer renderer(sharedContext(), assets, settings);
  renderer.render(r.list, 0, r.frame);
  return r;
}

}  // namespace sdg::test
