#pragma once
// Starting the renderer costs a 2-core machine about a quarter of a second
// before its first frame: loading Mesa and LLVM, creating the context, and
// compiling every shader variant at its first draw. None of that depends on
// the pre-roll, so a helper thread does it while the run's thread plays the
// first pre-roll. Given a warm-up frame (the stage as loaded, with the
// passes the run reads back), the helper also issues its draws with
// Renderer::compileFor(), so the shader variants are compiled too.
//
// A failure to create the context or the renderer is the run's failure and
// is rethrown by renderer(). A failure of the warm-up frame (a broken mesh
// on a prim that the behaviors may hide before any frame) is not: the
// helper's renderer is dropped and renderer() makes a fresh one, so the
// frames report it exactly where they would have.
#include <functional>
#include <memory>
#include <optional>
#include <thread>
#include <vector>

#include "render/raster/renderer.h"

namespace sdg {

struct WarmUpFrame {
  RenderList list;
  size_t cameraIndex = 0;
  PassSelection passes;
  // The entities whose coverage masks the run draws; none: it draws none.
  std::optional<std::vector<std::vector<size_t>>> coverageGroups;
};

class RendererBringUp {
 public:
  using ContextFactory = std::function<std::unique_ptr<GlContext>()>;
  RendererBringUp(ContextFactory makeContext, const AssetResolver& assets, const RenderSettings& settings,
                  std::optional<WarmUpFrame> warmUp);
  ~RendererBringUp();
  RendererBringUp(const RendererBringUp&) = delete;
  RendererBringUp& operator=(const RendererBringUp&) = delete;

  // Waits for the helper (the first call), rethrows what it threw, and makes
  // the context current on the calling thread, which must then be the only
  // one to use it.
  Renderer& renderer();
  GlContext& context();
  // Deletes the renderer and its context on a helper thread, so that their
  // teardown (llvmpipe's threads, compiled shaders, buffers) overlaps the
  // run's last writes; the destructor waits for it. Neither may be used
  // afterwards.
  void retireInBackground();

 private:
  void bringUp(std::optional<WarmUpFrame> warmUp);
  void join();

  ContextFactory makeContext_;
  const AssetResolver& assets_;
  RenderSettings settings_;
  std::thread thread_;
  std::exception_ptr error_;
  std::unique_ptr<GlContext> context_;
  std::unique_ptr<Renderer> renderer_;
  bool joined_ = false;
};

}  // namespace sdg
