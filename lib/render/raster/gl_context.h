#pragma once
// A current OpenGL 3.3+ core context with no window: rendering goes into
// framebuffer objects. Back ends: OSMesa (Mesa's llvmpipe, CPU) and EGL
// (a GPU through EGL's device platform, or Mesa's surfaceless llvmpipe).
#include <memory>
#include <string>

#include "render/raster/gl_api.h"

namespace sdg {

class GlContext {
 public:
  virtual ~GlContext() = default;
  const GlApi& gl() const { return gl_; }
  // "osmesa" or "egl"
  virtual std::string backend() const = 0;
  // Which device: "llvmpipe (CPU)", "EGL device 0 (/dev/dri/card0)", ...
  virtual std::string device() const = 0;
  // A context is current on the thread that created it. release() unbinds
  // it there so that another thread can makeCurrent() it (a renderer brought
  // up on a helper thread, then used by the run's thread). RunError on failure.
  virtual void makeCurrent() = 0;
  virtual void release() = 0;
  // GL_RENDERER / GL_VERSION strings, for the run summary.
  std::string rendererName() const;
  std::string versionName() const;

 protected:
  GlApi gl_;
};

// Creates an OSMesa core-profile 3.3 context, loading libOSMesa at run time
// so a machine without it gets a clear RunError naming what was tried.
std::unique_ptr<GlContext> createOsMesaContext();

struct EglSelection {
  int gpu = -1;             // device index among GPUs; -1: the first
  bool requireGpu = false;  // refuse the software fallback (auto uses this)
};
// Creates an EGL context: the chosen GPU device, or, with no GPU at all,
// Mesa's surfaceless platform. RunError names what failed.
std::unique_ptr<GlContext> createEglContext(const EglSelection& selection);
// True when libEGL loads and lists a device that is not software.
bool eglGpuAvailable();

// "auto": an EGL GPU when there is one, else OSMesa; "osmesa"; "egl".
std::unique_ptr<GlContext> createGlContext(const std::string& backend, int gpu);

}  // namespace sdg
