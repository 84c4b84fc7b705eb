#pragma once
// The GPU path tracer's own OpenGL context: 4.5 (or 4.3) core, for compute
// shaders, with no surface. It comes from EGL (render/egl/egl_devices.h,
// shared with the rasterizer): the GPU `--gpu` names among those the process
// sees, else Mesa's surfaceless platform (llvmpipe), so the same kernels run
// in CI on the CPU. It is separate from the rasterizer's 3.3
// context and lives on a thread of its own, where it stays current: the
// calling thread's current context (the rasterizer's, EGL or OSMesa, which
// share Mesa's dispatch) is never touched.
#include <GL/glcorearb.h>

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

namespace sdg {

// The tracer cannot run here (no EGL, no GL 4.3 compute, out of GPU
// memory): `auto` falls back to the CPU tracer on it.
class GpuUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

#define SDG_GL_COMPUTE_FUNCTIONS(X)                        \
  X(PFNGLGETSTRINGPROC, glGetString)                       \
  X(PFNGLGETERRORPROC, glGetError)                         \
  X(PFNGLGETINTEGERVPROC, glGetIntegerv)                   \
  X(PFNGLGETINTEGERI_VPROC, glGetIntegeri_v)               \
  X(PFNGLCREATESHADERPROC, glCreateShader)                 \
  X(PFNGLSHADERSOURCEPROC, glShaderSource)                 \
  X(PFNGLCOMPILESHADERPROC, glCompileShader)               \
  X(PFNGLGETSHADERIVPROC, glGetShaderiv)                   \
  X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog)         \
  X(PFNGLCREATEPROGRAMPROC, glCreateProgram)               \
  X(PFNGLATTACHSHADERPROC, glAttachShader)                 \
  X(PFNGLLINKPROGRAMPROC, glLinkProgram)                   \
  X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)                 \
  X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog)       \
  X(PFNGLUSEPROGRAMPROC, glUseProgram)                     \
  X(PFNGLDELETESHADERPROC, glDeleteShader)                 \
  X(PFNGLDELETEPROGRAMPROC, glDeleteProgram)               \
  X(PFNGLGENBUFFERSPROC, glGenBuffers)                     \
  X(PFNGLBINDBUFFERPROC, glBindBuffer)                     \
  X(PFNGLBUFFERDATAPROC, glBufferData)                     \
  X(PFNGLBUFFERSUBDATAPROC, glBufferSubData)               \
  X(PFNGLGETBUFFERSUBDATAPROC, glGetBufferSubData)         \
  X(PFNGLBINDBUFFERBASEPROC, glBindBufferBase)             \
  X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers)               \
  X(PFNGLDISPATCHCOMPUTEPROC, glDispatchCompute)           \
  X(PFNGLMEMORYBARRIERPROC, glMemoryBarrier)               \
  X(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation)     \
  X(PFNGLUNIFORM1IPROC, glUniform1i)                       \
  X(PFNGLUNIFORM1FPROC, glUniform1f)                       \
  X(PFNGLFINISHPROC, glFinish)                             \
  X(PFNGLFLUSHPROC, glFlush)                               \
  X(PFNGLGENQUERIESPROC, glGenQueries)                     \
  X(PFNGLDELETEQUERIESPROC, glDeleteQueries)               \
  X(PFNGLQUERYCOUNTERPROC, glQueryCounter)                 \
  X(PFNGLGETQUERYOBJECTUI64VPROC, glGetQueryObjectui64v)

// GL 4.4's, for reading the film back through pinned host memory; null on
// a 4.3 context, which reads it back with glGetBufferSubData instead.
#define SDG_GL_COMPUTE_OPTIONAL_FUNCTIONS(X)               \
  X(PFNGLBUFFERSTORAGEPROC, glBufferStorage)               \
  X(PFNGLMAPBUFFERRANGEPROC, glMapBufferRange)             \
  X(PFNGLCOPYBUFFERSUBDATAPROC, glCopyBufferSubData)       \
  X(PFNGLFENCESYNCPROC, glFenceSync)                       \
  X(PFNGLCLIENTWAITSYNCPROC, glClientWaitSync)             \
  X(PFNGLDELETESYNCPROC, glDeleteSync)

struct GlComputeApi {
#define SDG_DECLARE_GL(type, name) type name = nullptr;
  SDG_GL_COMPUTE_FUNCTIONS(SDG_DECLARE_GL)
  SDG_GL_COMPUTE_OPTIONAL_FUNCTIONS(SDG_DECLARE_GL)
#undef SDG_DECLARE_GL
};

class GlComputeContext {
 public:
  virtual ~GlComputeContext() = default;
  // The functions, to be called inside run() only.
  virtual const GlComputeApi& gl() const = 0;
  // "NVIDIA H100 PCIe/PCIe/SSE2, 4.5.0 NVIDIA ..." or "llvmpipe (LLVM ...), 4.5 (Core Profile) Mesa ..."
  virtual std::string description() const = 0;
  // True when the context runs on a GPU rather than Mesa's software device.
  virtual bool onGpu() const = 0;
  // Runs `task` on the context's thread, where the context is current, and
  // waits for it; rethrows what it throws. One task at a time.
  virtual void run(const std::function<void()>& task) = 0;
};

// GpuUnavailable when EGL is missing, `gpu` (an index among the visible
// GPUs; -1: the first) does not exist, or no context with GL 4.3 compute
// shaders can be made.
std::unique_ptr<GlComputeContext> createGlComputeContext(int gpu);
// Whether the process sees a GPU device (not Mesa's software one); makes no context.
bool eglGpuDeviceListed();

}  // namespace sdg
