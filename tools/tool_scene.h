#pragma once
// What the path tracers' developer tools (sdg_bench_pathtrace,
// sdg_tracer_agreement, sdg_denoise_quality) trace: a scene file's stage as
// loaded, without its behaviors, and its assets; and how they report a bad
// scene (exit 2) or a failure while tracing (exit 1) instead of crashing.
#include <cstdio>
#include <exception>
#include <string>

#include "assets/asset_resolver.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "core/diagnostics.h"
#include "render/pathtrace/path_tracer.h"
#include "render/render_list.h"
#include "scene_io/scene_loader.h"

namespace sdg {

struct ToolScene {
  Scene scene;
  RenderList list;
  AssetResolver assets;
  int maxBounces = 0;  // the scene's render.max_bounces

  // A tracer's settings for this scene: its bounces, these samples and threads.
  PathTraceSettings tracing(int samples, int threads) const { return {samples, maxBounces, threads}; }
};

inline ToolScene loadToolScene(const std::string& file) {
  ToolScene t;
  t.scene = loadScene(file, builtinRegistry().catalog());
  t.list = buildRenderList(t.scene.stage);
  t.assets = makeSceneResolver(t.scene.sourceDir, t.scene.assetRoots, {});
  t.maxBounces = int(t.scene.render.getUInt("max_bounces"));
  return t;
}

// Runs a tool's body; a scene it cannot load exits 2, any other failure 1,
// each with its message.
template <typename Body>
int runTool(const char* tool, Body&& body) {
  try {
    return body();
  } catch (const SceneError& e) {
    std::fprintf(stderr, "%s: %s\n", tool, e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", tool, e.what());
    return 1;
  }
}

}  // namespace sdg
