#include "render/raster/gl_context.h"

#include "core/diagnostics.h"

namespace sdg {

std::string GlContext::rendererName() const {
  const GLubyte* s = gl_.glGetString(GL_RENDERER);
  return s ? reinterpret_cast<const char*>(s) : "";
}

std::string GlContext::versionName() const {
  const GLubyte* s = gl_.glGetString(GL_VERSION);
  return s ? reinterpret_cast<const char*>(s) : "";
}

std::unique_ptr<GlContext> createGlContext(const std::string& backend, int gpu) {
  if (backend == "osmesa") {
    if (gpu >= 0) throw RunError("--gpu " + std::to_string(gpu) + " needs the EGL back end, not osmesa");
    return createOsMesaContext();
  }
  if (backend == "egl") return createEglContext(EglSelection{gpu, false});
  if (gpu >= 0 || eglGpuAvailable()) return createEglContext(EglSelection{gpu, true});
  return createOsMesaContext();
}

}  // namespace sdg
