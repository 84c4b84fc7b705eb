#include <dlfcn.h>

#include <array>
#include <vector>

#include "core/diagnostics.h"
#include "render/raster/gl_context.h"

// OSMesa's header gives the constants; the library itself is opened with
// dlopen so a machine without it gets a clear message instead of a loader error.
#include <GL/osmesa.h>

namespace {
using CreateAttribsFn = OSMesaContext (*)(const int*, OSMesaContext);
using MakeCurrentFn = GLboolean (*)(OSMesaContext, void*, GLenum, GLsizei, GLsizei);
using GetProcFn = OSMESAproc (*)(const char*);
using DestroyFn = void (*)(OSMesaContext);
}  // namespace

namespace sdg {

namespace {

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext() {
    const std::array<const char*, 3> names = {"libOSMesa.so.8", "libOSMesa.so.6", "libOSMesa.so"};
    std::string tried;
    for (const char* name : names) {
      library_ = dlopen(name, RTLD_NOW | RTLD_LOCAL);
      if (library_) break;
      tried += std::string(tried.empty() ? "" : ", ") + name;
    }
    if (!library_)
      throw RunError("OSMesa back end: cannot load " + tried +
                     " (install Debian's libosmesa6; `make deps` does it)");
    auto create = reinterpret_cast<CreateAttribsFn>(dlsym(library_, "OSMesaCreateContextAttribs"));
    makeCurrent_ = reinterpret_cast<MakeCurrentFn>(dlsym(library_, "OSMesaMakeCurrent"));
    auto getProc = reinterpret_cast<GetProcFn>(dlsym(library_, "OSMesaGetProcAddress"));
    destroy_ = reinterpret_cast<DestroyFn>(dlsym(library_, "OSMesaDestroyContext"));
    if (!create || !makeCurrent_ || !getProc || !destroy_)
      throw RunError("OSMesa back end: the library lacks OSMesaCreateContextAttribs (Mesa 12 or newer is needed)");
    const int attribs[] = {OSMESA_FORMAT,  OSMESA_RGBA, OSMESA_DEPTH_BITS,           24, OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    context_ = create(attribs, nullptr);
    if (!context_) throw RunError("OSMesa back end: cannot create an OpenGL 3.3 core profile context");
    makeCurrent();
    if (std::string missing = gl_.load([getProc](const char* name) { return reinterpret_cast<void*>(getProc(name)); });
        !missing.empty())
      throw RunError("OSMesa back end: the GL function " + missing + " is missing");
  }

  ~OsMesaContext() override {
    if (context_) destroy_(context_);
    // The library stays loaded: Mesa registers atexit handlers.
  }

  // OSMesa needs a buffer to make the context current; frames go to FBOs.
  void makeCurrent() override {
    if (!makeCurrent_(context_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1))
      throw RunError("OSMesa back end: cannot make the context current");
  }
  void release() override { makeCurrent_(nullptr, nullptr, 0, 0, 0); }

  std::string backend() const override { return "osmesa"; }
  std::string device() const override { return "CPU (OSMesa)"; }

 private:
  void* library_ = nullptr;
  OSMesaContext context_ = nullptr;
  MakeCurrentFn makeCurrent_ = nullptr;
  DestroyFn destroy_ = nullptr;
  std::array<unsigned char, 4> buffer_{};
};

}  // namespace

std::unique_ptr<GlContext> createOsMesaContext() { return std::make_unique<OsMesaContext>(); }


}  // namespace sdg
