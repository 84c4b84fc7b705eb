#include "render/pathtrace/gpu/gl_compute.h"

#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "render/egl/egl_devices.h"

namespace sdg {
namespace {

// The context itself, made and used on one thread (ThreadedContext's).
class EglComputeContext {
 public:
  explicit EglComputeContext(int gpu) {
    std::string why;
    const egl::Api* api = egl::api(&why);
    if (!api) throw GpuUnavailable("GPU path tracer: " + why);
    const egl::Api& egl = *api;
    makeCurrent_ = egl.makeCurrent;
    destroyContext_ = egl.destroyContext;
    auto getProc = egl.getProcAddress;
    std::string problem;
    const std::vector<egl::Gpu> gpus = egl::visibleGpus(egl, &problem);
    if (!problem.empty()) throw GpuUnavailable("GPU path tracer: " + problem);
    if (gpu >= 0 && size_t(gpu) >= gpus.size())
      throw GpuUnavailable("GPU path tracer: --gpu " + std::to_string(gpu) + " is out of range; this process sees " +
                           std::to_string(gpus.size()) + " GPU device(s)");
    const size_t index = gpu >= 0 ? size_t(gpu) : 0;
    onGpu_ = !gpus.empty();  // else llvmpipe
    device_ = onGpu_ ? egl::describe(gpus[index], int(index)) : "EGL surfaceless (software)";
    display_ = onGpu_ ? egl.getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, gpus[index].device, nullptr)
                      : egl.getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    auto initialize = egl.initialize;
    auto bindApi = egl.bindApi;
    auto chooseConfig = egl.chooseConfig;
    auto createContext = egl.createContext;
    auto queryString = egl.queryString;
    EGLint major = 0, minor = 0;
    if (display_ == EGL_NO_DISPLAY || !initialize(display_, &major, &minor) || !bindApi(EGL_OPENGL_API))
      throw GpuUnavailable("GPU path tracer: no EGL display with desktop OpenGL");
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!egl::hasExtension(queryString(display_, EGL_EXTENSIONS), "EGL_KHR_no_config_context")) {
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
    if (!makeCurrent_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw GpuUnavailable("GPU path tracer: cannot make its context current");
#define SDG_LOAD_GL(type, name)                                                                     \
  gl_.name = reinterpret_cast<type>(getProc(#name));                                                \
  if (!gl_.name) throw GpuUnavailable("GPU path tracer: the OpenGL function " #name " is missing");
    SDG_GL_COMPUTE_FUNCTIONS(SDG_LOAD_GL)
#undef SDG_LOAD_GL
    GLint version[2] = {0, 0};
    gl_.glGetIntegerv(GL_MAJOR_VERSION, &version[0]);
    gl_.glGetIntegerv(GL_MINOR_VERSION, &version[1]);
    // SDG_GPU_GL43=1 takes the GL 4.3 way on any context, so tests reach it.
    const char* gl43 = std::getenv("SDG_GPU_GL43");
    const bool force43 = gl43 && *gl43 && std::string(gl43) != "0";
    if (version[0] * 10 + version[1] >= 44 && !force43) {  // else they stay null (a stub from getProc may not work)
#define SDG_LOAD_OPTIONAL_GL(type, name) gl_.name = reinterpret_cast<type>(getProc(#name));
      SDG_GL_COMPUTE_OPTIONAL_FUNCTIONS(SDG_LOAD_OPTIONAL_GL)
#undef SDG_LOAD_OPTIONAL_GL
      if (!gl_.glBufferStorage || !gl_.glMapBufferRange || !gl_.glCopyBufferSubData || !gl_.glFenceSync ||
          !gl_.glClientWaitSync || !gl_.glDeleteSync)
        gl_.glBufferStorage = nullptr;  // the read-back then takes the 4.3 way
    }
    description_ = std::string(reinterpret_cast<const char*>(gl_.glGetString(GL_RENDERER))) + ", " +
                   reinterpret_cast<const char*>(gl_.glGetString(GL_VERSION)) + " on " + device_;
  }

  ~EglComputeContext() {
    if (context_ != EGL_NO_CONTEXT) {
      makeCurrent_(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      destroyContext_(display_, context_);
    }
    // The display stays initialised and libEGL loaded, as in the rasterizer's back end.
  }

  const GlComputeApi& gl() const { return gl_; }
  std::string description() const { return description_; }
  bool onGpu() const { return onGpu_; }

 private:
  PFNEGLMAKECURRENTPROC makeCurrent_ = nullptr;
  PFNEGLDESTROYCONTEXTPROC destroyContext_ = nullptr;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  GlComputeApi gl_;
  bool onGpu_ = false;
  std::string device_;
  std::string description_;
};

// Owns the thread the context lives on; run() hands it one task at a time.
class ThreadedContext final : public GlComputeContext {
 public:
  explicit ThreadedContext(int gpu) : thread_([this] { loop(); }) {
    try {
      run([this, gpu] { context_ = std::make_unique<EglComputeContext>(gpu); });
    } catch (...) {
      stop();
      throw;
    }
  }
  ~ThreadedContext() override {
    try {
      run([this] { context_.reset(); });
    } catch (...) {  // going away; nothing to report to
    }
    stop();
  }

  const GlComputeApi& gl() const override { return context_->gl(); }
  std::string description() const override { return context_->description(); }
  bool onGpu() const override { return context_->onGpu(); }

  void run(const std::function<void()>& task) override {
    std::unique_lock<std::mutex> lock(mutex_);
    task_ = &task;
    failure_ = nullptr;
    wake_.notify_all();
    done_.wait(lock, [this] { return task_ == nullptr; });
    if (failure_) std::rethrow_exception(failure_);
  }

 private:
  void loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      wake_.wait(lock, [this] { return task_ != nullptr || stopping_; });
      if (!task_) return;
      try {
        (*task_)();
      } catch (...) {
        failure_ = std::current_exception();
      }
      task_ = nullptr;
      done_.notify_all();
    }
  }
  void stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void()>* task_ = nullptr;
  std::exception_ptr failure_;
  bool stopping_ = false;
  std::unique_ptr<EglComputeContext> context_;
  std::thread thread_;  // last: started once the members it uses exist
};

}  // namespace

std::unique_ptr<GlComputeContext> createGlComputeContext(int gpu) { return std::make_unique<ThreadedContext>(gpu); }

bool eglGpuDeviceListed() {
  const egl::Api* api = egl::api();
  return api && !egl::visibleGpus(*api).empty();
}

}  // namespace sdg
