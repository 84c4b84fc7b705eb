#pragma once
// What the path tracers' developer tools (sdg_bench_pathtrace,
// sdg_tracer_agreement, sdg_denoise_quality) trace: a scene file's stage as
// loaded, without its behaviors, and its assets; and how they report a bad
// scene (exit 2) or a failure while tracing (exit 1) instead of crashing.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>

#include "assets/asset_resolver.h"
#include "builtin_behaviors/builtin_behaviors.h"
#include "core/diagnostics.h"
#include "render/pathtrace/path_tracer.h"
#include "render/render_list.h"
#include "scene_io/scene_loader.h"
#include "scene_io/usd_mesh_asset.h"

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
  registerUsdMeshAssets();  // `asset: x.usd` meshes
  t.scene = loadScene(file, builtinRegistry().catalog());
  t.list = buildRenderList(t.scene.stage);
  t.assets = makeSceneResolver(t.scene.sourceDir, t.scene.assetRoots, {});
  t.maxBounces = int(t.scene.render.getUInt("max_bounces"));
  return t;
}

// A mistake in a tool's arguments: runTool prints it and exits 2.
struct ToolUsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// An argument that must be a whole number of at least `least`; `what` names it in the message.
inline int toolInt(const char* what, const char* text, int least) {
  int value = 0;
  const char* end = text + std::strlen(text);
  const auto [at, error] = std::from_chars(text, end, value);
  if (error != std::errc() || at != end || value < least)
    throw ToolUsageError(std::string(what) + " must be a whole number of at least " + std::to_string(least) +
                         ", got '" + text + "'");
  return value;
}

// An argument that must be a finite number; `what` names it in the message.
inline float toolFloat(const char* what, const char* text) {
  float value = 0.0f;
  const char* end = text + std::strlen(text);
  const auto [at, error] = std::from_chars(text, end, value);
  if (error != std::errc() || at != end || !std::isfinite(value))
    throw ToolUsageError(std::string(what) + " must be a number, got '" + text + "'");
  return value;
}

// Runs a tool's body; a mistake in its arguments or a scene it cannot load
// exits 2, any other failure 1, each with its message.
template <typename Body>
int runTool(const char* tool, Body&& body) {
  try {
    return body();
  } catch (const ToolUsageError& e) {
    std::fprintf(stderr, "%s: %s\n", tool, e.what());
    return 2;
  } catch (const SceneError& e) {
    std::fprintf(stderr, "%s: %s\n", tool, e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", tool, e.what());
    return 1;
  }
}

}  // namespace sdg
