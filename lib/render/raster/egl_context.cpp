// The EGL back end: OpenGL 3.3 core with no display and no surface, drawing
// into the same framebuffer objects as OSMesa. GPUs come from EGL's device
// platform (EGL_EXT_device_enumeration + EGL_EXT_platform_device); with no
// GPU, Mesa's surfaceless platform gives llvmpipe, so this path runs in CI.
// libEGL is opened with dlopen: a machine without it gets a clear message.
#include <dlfcn.h>

#include <cstdio>
#include <string>
#include <type_traits>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "core/diagnostics.h"
#include "render/raster/gl_context.h"

namespace sdg {
namespace {

struct EglApi {
  void* library = nullptr;
  PFNEGLGETPROCADDRESSPROC getProcAddress = nullptr;
  PFNEGLINITIALIZEPROC initialize = nullptr;
  PFNEGLBINDAPIPROC bindApi = nullptr;
  PFNEGLCHOOSECONFIGPROC chooseConfig = nullptr;
  PFNEGLCREATECONTEXTPROC createContext = nullptr;
  PFNEGLDESTROYCONTEXTPROC destroyContext = nullptr;
  PFNEGLMAKECURRENTPROC makeCurrent = nullptr;
  PFNEGLGETERRORPROC getError = nullptr;
  PFNEGLQUERYSTRINGPROC queryString = nullptr;
  PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;
  PFNEGLQUERYDEVICESTRINGEXTPROC queryDeviceString = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay = nullptr;

  void load() {
    library = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!library)
      throw RunError("EGL back end: cannot load libEGL.so.1 (install Debian's libegl1 and a vendor: libegl-mesa0, "
                     "or the GPU driver's)");
    getProcAddress = reinterpret_cast<PFNEGLGETPROCADDRESSPROC>(dlsym(library, "eglGetProcAddress"));
    if (!getProcAddress) throw RunError("EGL back end: libEGL.so.1 has no eglGetProcAddress");
    auto need = [&](auto& fn, const char* name) {
      fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(getProcAddress(name));
      if (!fn) throw RunError(std::string("EGL back end: libEGL lacks ") + name);
    };
    need(initialize, "eglInitialize");
    need(bindApi, "eglBindAPI");
    need(chooseConfig, "eglChooseConfig");
    need(createContext, "eglCreateContext");
    need(destroyContext, "eglDestroyContext");
    need(makeCurrent, "eglMakeCurrent");
    need(getError, "eglGetError");
    need(queryString, "eglQueryString");
    need(getPlatformDisplay, "eglGetPlatformDisplayEXT");
    // Device enumeration is optional: without it only the surfaceless platform is tried.
    queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(getProcAddress("eglQueryDevicesEXT"));
    queryDeviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(getProcAddress("eglQueryDeviceStringEXT"));
  }
};

std::string hex(EGLint error) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%04X", unsigned(error));
  return text;
}

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const std::string all = std::string(" ") + list + " ";
  return all.find(std::string(" ") + name + " ") != std::string::npos;
}

// Devices that are GPUs: Mesa also lists a software device, which the
// surfaceless platform covers.
std::vector<EGLDeviceEXT> gpuDevices(const EglApi& egl) {
  std::vector<EGLDeviceEXT> out;
  if (!egl.queryDevices) return out;
  EGLint n = 0;
  if (!egl.queryDevices(0, nullptr, &n) || n <= 0) return out;
  std::vector<EGLDeviceEXT> all(static_cast<size_t>(n));
  if (!egl.queryDevices(n, all.data(), &n)) return out;
  for (EGLint i = 0; i < n; ++i) {
    const char* ext = egl.queryDeviceString ? egl.queryDeviceString(all[size_t(i)], EGL_EXTENSIONS) : nullptr;
    if (!hasExtension(ext, "EGL_MESA_device_software")) out.push_back(all[size_t(i)]);
  }
  return out;
}

class EglContext final : public GlContext {
 public:
  explicit EglContext(const EglSelection& selection) {
    egl_.load();
    std::vector<EGLDeviceEXT> gpus = gpuDevices(egl_);
    if (selection.requireGpu && gpus.empty())
      throw RunError("EGL back end: no GPU device (EGL_EXT_device_enumeration found none besides software ones)");
    if (selection.gpu >= 0 && size_t(selection.gpu) >= gpus.size() && !gpus.empty())
      throw RunError("EGL back end: --gpu " + std::to_string(selection.gpu) + " is out of range; this machine has " +
                     std::to_string(gpus.size()) + " GPU device(s), numbered from 0");
    if (selection.gpu > 0 && gpus.empty())
      throw RunError("EGL back end: --gpu " + std::to_string(selection.gpu) + " asked for, but there is no GPU device");
    if (!gpus.empty()) {
      const size_t index = selection.gpu >= 0 ? size_t(selection.gpu) : 0;
      display_ = egl_.getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, gpus[index], nullptr);
      device_ = "EGL device " + std::to_string(index);
      if (egl_.queryDeviceString)
        if (const char* drm = egl_.queryDeviceString(gpus[index], EGL_DRM_DEVICE_FILE_EXT)) device_ += " (" + std::string(drm) + ")";
    } else {
      display_ = egl_.getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      device_ = "EGL surfaceless (software)";
    }
    if (display_ == EGL_NO_DISPLAY) throw RunError("EGL back end: no display for " + device_ + ": " + hex(egl_.getError()));
    EGLint major = 0, minor = 0;
    if (!egl_.initialize(display_, &major, &minor))
      throw RunError("EGL back end: eglInitialize failed on " + device_ + ": " + hex(egl_.getError()));
    if (!egl_.bindApi(EGL_OPENGL_API)) throw RunError("EGL back end: " + device_ + " has no desktop OpenGL");
    // Frames go to framebuffer objects, so any configuration will do; a
    // display with EGL_KHR_no_config_context needs none at all.
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!hasExtension(egl_.queryString(display_, EGL_EXTENSIONS), "EGL_KHR_no_config_context")) {
      const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
      EGLint count = 0;
      if (!egl_.chooseConfig(display_, configAttribs, &config, 1, &count) || count < 1)
        throw RunError("EGL back end: " + device_ + " offers no OpenGL configuration");
    }
    const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                     EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    context_ = egl_.createContext(display_, config, EGL_NO_CONTEXT, contextAttribs);
    if (context_ == EGL_NO_CONTEXT)
      throw RunError("EGL back end: " + device_ + " cannot create an OpenGL 3.3 core context: " + hex(egl_.getError()));
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
                     hex(egl_.getError()));
  }
  void release() override { egl_.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT); }

  std::string backend() const override { return "egl"; }
  std::string device() const override { return device_; }

 private:
  EglApi egl_;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string device_;
};

}  // namespace

std::unique_ptr<GlContext> createEglContext(const EglSelection& selection) {
  return std::make_unique<EglContext>(selection);
}

bool eglGpuAvailable() {
  try {
    EglApi egl;
    egl.load();
    return !gpuDevices(egl).empty();
  } catch (const RunError&) {
    return false;
  }
}

}  // namespace sdg
