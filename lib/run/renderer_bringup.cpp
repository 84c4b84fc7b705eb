#include "run/renderer_bringup.h"

namespace sdg {

RendererBringUp::RendererBringUp(ContextFactory makeContext, const AssetResolver& assets,
                                 const RenderSettings& settings, std::optional<WarmUpFrame> warmUp)
    : makeContext_(std::move(makeContext)), assets_(assets), settings_(settings) {
  thread_ = std::thread([this, frame = std::move(warmUp)]() mutable { bringUp(std::move(frame)); });
}

void RendererBringUp::bringUp(std::optional<WarmUpFrame> warmUp) {
  try {
    context_ = makeContext_();
    renderer_ = std::make_unique<Renderer>(*context_, assets_, settings_);
  } catch (...) {
    error_ = std::current_exception();
    renderer_.reset();
    context_.reset();
    return;
  }
  if (warmUp) {
    try {
      renderer_->compileFor(warmUp->list, warmUp->cameraIndex, warmUp->passes,
                            warmUp->coverageGroups ? &*warmUp->coverageGroups : nullptr);
    } catch (...) {
      renderer_.reset();  // its GL objects go while the context is current here
      context_.reset();
      return;
    }
  }
  context_->release();
}

void RendererBringUp::join() {
  if (joined_) return;
  thread_.join();
  joined_ = true;
}

Renderer& RendererBringUp::renderer() {
  if (!joined_) {
    join();
    if (renderer_) context_->makeCurrent();
  }
  if (error_) std::rethrow_exception(error_);
  if (!renderer_) {  // the warm-up failed: start again here, with no warm-up
    context_ = makeContext_();
    renderer_ = std::make_unique<Renderer>(*context_, assets_, settings_);
  }
  return *renderer_;
}

GlContext& RendererBringUp::context() {
  renderer();
  return *context_;
}

void RendererBringUp::retireInBackground() {
  renderer();  // joined, and current here
  context_->release();
  joined_ = false;
  thread_ = std::thread([this] {
    try {
      context_->makeCurrent();
    } catch (...) {
      (void)renderer_.release();  // as in the destructor: it goes with the process
    }
    renderer_.reset();
    context_.reset();
  });
}

RendererBringUp::~RendererBringUp() {
  const bool wasJoined = joined_;
  join();
  // The renderer's GL objects are deleted through a context current here.
  if (!wasJoined && renderer_) {
    try {
      context_->makeCurrent();
    } catch (...) {
      // Without a context its GL objects cannot be deleted; the context
      // goes with the process.
      (void)renderer_.release();
    }
  }
  renderer_.reset();
  context_.reset();
}

}  // namespace sdg
