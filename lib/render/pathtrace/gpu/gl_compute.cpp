#include "render/pathtrace/gpu/gl_compute.h"

#include <dlfcn.h>

#include <string>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>

namespace sdg {
namespace {

template <typename Fn>
Fn eglFunction(PFNEGLGETPROCADDRESSPROC getProc, const char* name) {
  Fn fn = reinterpret_cast<Fn>(getProc(name));
  if (!fn) throw GpuUnavailable(std::string("GPU path tracer: libEGL lacks ") + name);
  return fn;
}

bool listed(const char* list, const char* name) {
  if (!list) return false;
  const std::string all = std::string(" ") + list + " ";
  return all.find(std::string(" ") + name + " ") != std::string::npos;
}

// The first GPU device of EGL's device platform; Mesa also lists a
// software one, which the surfaceless platform covers.
EGLDeviceEXT firstGpuDevice(PFNEGLGETPROCADDRESSPROC getProc) {
  auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(getProc("eglQueryDevicesEXT"));
  auto deviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(getProc("eglQueryDeviceStringEXT"));
  EGLint count = 0;
  if (!queryDevices || !queryDevices(0, nullptr, &count) || count <= 0) return nullptr;
  std::vector<EGLDeviceEXT> all(static_cast<size_t>(count));
  if (!queryDevices(count, all.data(), &count)) return nullptr;
  for (EGLint i = 0; i < count; ++i)
    if (!listed(deviceString ? deviceString(all[size_t(i)], EGL_EXTENSIONS) : nullptr, "EGL_MESA_device_software"))
      return all[size_t(i)];
  return nullptr;
}

PFNEGLGETPROCADDRESSPROC loadEgl(void*& library) {
  library = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
  if (!library) return nullptr;
  return reinterpret_cast<PFNEGLGETPROCADDRESSPROC>(dlsym(library, "eglGetProcAddress"));
}

class EglComputeContext final : public GlComputeContext {
 public:
  EglComputeContext() {
    auto getProc = loadEgl(library_);
    if (!getProc) throw GpuUnavailable("GPU path tracer: cannot load libEGL.so.1 (or it has no eglGetProcAddress)");
    makeCurrent_ = eglFunction<PFNEGLMAKECURRENTPROC>(getProc, "eglMakeCurrent");
    getCurrentContext_ = eglFunction<PFNEGLGETCURRENTCONTEXTPROC>(getProc, "eglGetCurrentContext");
    getCurrentDisplay_ = eglFunction<PFNEGLGETCURRENTDISPLAYPROC>(getProc, "eglGetCurrentDisplay");
    getCurrentSurface_ = eglFunction<PFNEGLGETCURRENTSURFACEPROC>(getProc, "eglGetCurrentSurface");
    destroyContext_ = eglFunction<PFNEGLDESTROYCONTEXTPROC>(getProc, "eglDestroyContext");
    auto initialize = eglFunction<PFNEGLINITIALIZEPROC>(getProc, "eglInitialize");
    auto bindApi = eglFunction<PFNEGLBINDAPIPROC>(getProc, "eglBindAPI");
    auto chooseConfig = eglFunction<PFNEGLCHOOSECONFIGPROC>(getProc, "eglChooseConfig");
    auto createContext = eglFunction<PFNEGLCREATECONTEXTPROC>(getProc, "eglCreateContext");
    auto queryString = eglFunction<PFNEGLQUERYSTRINGPROC>(getProc, "eglQueryString");
    auto platformDisplay = eglFunction<PFNEGLGETPLATFORMDISPLAYEXTPROC>(getProc, "eglGetPlatformDisplayEXT");
    EGLDeviceEXT gpu = firstGpuDevice(getProc);  // else llvmpipe
    onGpu_ = gpu != nullptr;
    display_ = gpu ? platformDisplay(EGL_PLATFORM_DEVICE_EXT, gpu, nullptr)
                   : platformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major = 0, minor = 0;
    if (display_ == EGL_NO_DISPLAY || !initialize(display_, &major, &minor) || !bindApi(EGL_OPENGL_API))
      throw GpuUnavailable("GPU path tracer: no EGL display with desktop OpenGL");
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!listed(queryString(display_, EGL_EXTENSIONS), "EGL_KHR_no_config_context")) {
      const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
      EGLint found = 0;
      if (!chooseConfig(display_, attribs, &config, 1, &found) || found < 1)
        throw GpuUnavailable("GPU path tracer: the EGL display offers no OpenGL configuration");
    }
    for (const EGLint minorVersion : {5, 3}) {
      const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, minorVersion,
                                EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
      context_ = createContext(display_, config, EGL_NO_CONTEXT, attribs);
      if (context_ != EGL_NO_CONTEXT) break;
    }
    if (context_ == EGL_NO_CONTEXT)
      throw GpuUnavailable("GPU path tracer: the device offers no OpenGL 4.3 core context (compute shaders)");
    Scope scope(*this);
#define SDG_LOAD_GL(type, name)                                                                     \
  gl_.name = reinterpret_cast<type>(getProc(#name));                                                \
  if (!gl_.name) throw GpuUnavailable("GPU path tracer: the OpenGL function " #name " is missing");
    SDG_GL_COMPUTE_FUNCTIONS(SDG_LOAD_GL)
#undef SDG_LOAD_GL
    description_ = std::string(reinterpret_cast<const char*>(gl_.glGetString(GL_RENDERER))) + ", " +
                   reinterpret_cast<const char*>(gl_.glGetString(GL_VERSION));
  }

  ~EglComputeContext() override {
    if (context_ != EGL_NO_CONTEXT) {
      if (getCurrentContext_() == context_) makeCurrent_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      destroyContext_(display_, context_);
    }
    // The display stays initialised and libEGL loaded, as in the rasterizer's back end.
  }

  std::string description() const override { return description_; }
  bool onGpu() const override { return onGpu_; }

 protected:
  void enter() override {
    savedDisplay_ = getCurrentDisplay_();
    savedContext_ = getCurrentContext_();
    savedDraw_ = getCurrentSurface_(EGL_DRAW);
    savedRead_ = getCurrentSurface_(EGL_READ);
    if (!makeCurrent_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw GpuUnavailable("GPU path tracer: cannot make its context current");
  }
  void leave() override {
    if (savedContext_ != EGL_NO_CONTEXT && savedDisplay_ != EGL_NO_DISPLAY)
      makeCurrent_(savedDisplay_, savedDraw_, savedRead_, savedContext_);
    else
      makeCurrent_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }

 private:
  void* library_ = nullptr;
  PFNEGLMAKECURRENTPROC makeCurrent_ = nullptr;
  PFNEGLGETCURRENTCONTEXTPROC getCurrentContext_ = nullptr;
  PFNEGLGETCURRENTDISPLAYPROC getCurrentDisplay_ = nullptr;
  PFNEGLGETCURRENTSURFACEPROC getCurrentSurface_ = nullptr;
  PFNEGLDESTROYCONTEXTPROC destroyContext_ = nullptr;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLDisplay savedDisplay_ = EGL_NO_DISPLAY;
  EGLContext savedContext_ = EGL_NO_CONTEXT;
  EGLSurface savedDraw_ = EGL_NO_SURFACE, savedRead_ = EGL_NO_SURFACE;
  bool onGpu_ = false;
  std::string description_;
};

}  // namespace

std::unique_ptr<GlComputeContext> createGlComputeContext() { return std::make_unique<EglComputeContext>(); }

bool eglGpuDeviceListed() {
  void* library = nullptr;
  auto getProc = loadEgl(library);
  return getProc && firstGpuDevice(getProc) != nullptr;  // libEGL stays loaded, as for the contexts
}

}  // namespace sdg
