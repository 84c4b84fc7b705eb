// The EGL back end: OpenGL 3.3 core with no display and no surface, drawing
// into the same framebuffer objects as OSMesa. GPUs come from EGL's device
// platform (EGL_EXT_device_enumeration + EGL_EXT_platform_device); with no
// GPU, Mesa's surfaceless platform gives llvmpipe, so this path runs in CI.
// libEGL and the device are found by render/egl/egl_devices.h, as for the GPU
// path tracer's context.
#include <cstdio>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "render/egl/egl_devices.h"
#include "render/raster/gl_context.h"

namespace sdg {
namespace {

using egl::hexError;

class EglContext final : public GlContext {
 public:
  explicit EglContext(const EglSelection& selection) {
    std::string why;
    const egl::Api* api = egl::api(&why);
    if (!api) throw RunError("EGL back end: " + why);
    egl_ = *api;
    std::string problem;
    std::vector<egl::Gpu> gpus = egl::visibleGpus(egl_, &problem);
    if (!problem.empty()) throw RunError("EGL back end: " + problem);
    if (selection.requireGpu && gpus.empty())
      throw RunError("EGL back end: no GPU device (EGL_EXT_device_enumeration found none besides software ones)");
    if (selection.gpu >= 0 && size_t(selection.gpu) >= gpus.size() && !gpus.empty())
      throw RunError("EGL back end: --gpu " + std::to_string(selection.gpu) + " is out of range; this process sees " +
                     std::to_string(gpus.size()) + " GPU device(s), numbered from 0");
    if (selection.gpu > 0 && gpus.empty())
      throw RunError("EGL back end: --gpu " + std::to_string(selection.gpu) + " asked for, but there is no GPU device");
    if (!gpus.empty()) {
      const size_t index = selection.gpu >= 0 ? size_t(selection.gpu) : 0;
      display_ = egl_.getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, gpus[index].device, nullptr);
      device_ = egl::describe(gpus[index], int(index));
    } else {
      display_ = egl_.getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      device_ = "EGL surfaceless (software)";
    }
    if (display_ == EGL_NO_DISPLAY) throw RunError("EGL back end: no display for " + device_ + ": " + hexError(egl_.getError()));
    EGLint major = 0, minor = 0;
    if (!egl_.initialize(display_, &major, &minor))
      throw RunError("EGL back end: eglInitialize failed on " + device_ + ": " + hexError(egl_.getError()));
    if (!egl_.bindApi(EGL_OPENGL_API)) throw RunError("EGL back end: " + device_ + " has no desktop OpenGL");
    // Frames go to framebuffer objects, so any configuration will do; a
    // display with EGL_KHR_no_config_context needs none at all.
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!egl::hasExtension(egl_.queryString(display_, EGL_EXTENSIONS), "EGL_KHR_no_config_context")) {
      const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
      EGLint count = 0;
      if (!egl_.chooseConfig(display_, configAttribs, &config, 1, &count) || count < 1)
        throw RunError("EGL back end: " + device_ + " offers no OpenGL configuration");
    }
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    context_ = egl_.createContext(display_, config, EGL_NO_CONTEXT, contextAttribs);
    if (context_ == EGL_NO_CONTEXT)
      throw RunError("EGL back end: " + device_ + " cannot create an OpenGL 3.3 core context: " + hexError(egl_.getError()));
    makeCurrent();
    auto getProc = egl_.getProcAddress;
    if (std::string missing = gl_.load([getProc](const char* name) { return reinterpret_cast<void*>(getProc(name)); });
        !missing.empty())
      throw RunError("EGL back end: the GL function " + missing + " is missing");
  }

  // The display stays initialised (no eglTerminate): drivers keep
  // process-lifetime state, and unloading them mid-process only hides it.
  ~EglContext() override {
    if (display_ != EGL_NO_DISPLAY) {
      egl_.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (context_ != EGL_NO_CONTEXT) egl_.destroyContext(display_, context_);
    }
  }

  void makeCurrent() override {
    if (!egl_.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw RunError("EGL back end: cannot make the context current without a surface on " + device_ + ": " +
                     hexError(egl_.getError()));
  }
  void release() override { egl_.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT); }

  std::string backend() const override { return "egl"; }
  std::string device() const override { return device_; }

 private:
  egl::Api egl_;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string device_;
};

}  // namespace

std::unique_ptr<GlContext> createEglContext(const EglSelection& selection) {
  return std::make_unique<EglContext>(selection);
}

bool eglGpuAvailable() {
  const egl::Api* api = egl::api();
  return api && !egl::visibleGpus(*api).empty();
}

}  // namespace sdg
