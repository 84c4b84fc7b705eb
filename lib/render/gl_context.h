#pragma once
// A current OpenGL 3.3+ core context with no window: rendering goes into
// framebuffer objects. Back ends: OSMesa (Mesa's llvmpipe, CPU) today.
#include <memory>
#include <string>

#include "render/gl_api.h"

namespace sdg {

class GlContext {
 public:
  virtual ~GlContext() = default;
  const GlApi& gl() const { return gl_; }
  // "osmesa"
  virtual std::string backend() const = 0;
  // GL_RENDERER / GL_VERSION strings, for the run summary.
  std::string rendererName() const;
  std::string versionName() const;

 protected:
  GlApi gl_;
};

// Creates an OSMesa core-profile 3.3 context, loading libOSMesa at run time
// so a machine without it gets a clear RunError naming what was tried.
std::unique_ptr<GlContext> createOsMesaContext();

}  // namespace sdg
