#include "render/egl/egl_devices.h"

#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <sstream>
#include <type_traits>

namespace sdg::egl {
namespace {

struct Loaded {
  Api api;
  std::string why;  // empty when loaded
};

Loaded load() {
  Loaded out;
  void* library = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
  if (!library) {
    out.why = "cannot load libEGL.so.1 (install Debian's libegl1 and a vendor: libegl-mesa0, or the GPU driver's)";
    return out;
  }
  Api& a = out.api;
  a.getProcAddress = reinterpret_cast<PFNEGLGETPROCADDRESSPROC>(dlsym(library, "eglGetProcAddress"));
  if (!a.getProcAddress) {
    out.why = "libEGL.so.1 has no eglGetProcAddress";
    return out;
  }
  auto need = [&](auto& fn, const char* name) {
    fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(a.getProcAddress(name));
    if (!fn && out.why.empty()) out.why = std::string("libEGL lacks ") + name;
  };
  need(a.initialize, "eglInitialize");
  need(a.bindApi, "eglBindAPI");
  need(a.chooseConfig, "eglChooseConfig");
  need(a.createContext, "eglCreateContext");
  need(a.destroyContext, "eglDestroyContext");
  need(a.makeCurrent, "eglMakeCurrent");
  need(a.getError, "eglGetError");
  need(a.queryString, "eglQueryString");
  need(a.getPlatformDisplay, "eglGetPlatformDisplayEXT");
  // Device enumeration is optional: without it only the surfaceless platform is used.
  a.queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(a.getProcAddress("eglQueryDevicesEXT"));
  a.queryDeviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(a.getProcAddress("eglQueryDeviceStringEXT"));
  return out;
}

// Every GPU device of the machine, in EGL's order.
std::vector<Gpu> machineGpus(const Api& egl) {
  std::vector<Gpu> out;
  EGLint n = 0;
  if (!egl.queryDevices || !egl.queryDevices(0, nullptr, &n) || n <= 0) return out;
  std::vector<EGLDeviceEXT> all(static_cast<size_t>(n));
  if (!egl.queryDevices(n, all.data(), &n)) return out;
  for (EGLint i = 0; i < n; ++i) {
    EGLDeviceEXT d = all[size_t(i)];
    const char* ext = egl.queryDeviceString ? egl.queryDeviceString(d, EGL_EXTENSIONS) : nullptr;
    if (hasExtension(ext, "EGL_MESA_device_software")) continue;
    Gpu gpu;
    gpu.device = d;
    gpu.machineIndex = int(out.size());
    if (egl.queryDeviceString)
      if (const char* drm = egl.queryDeviceString(d, EGL_DRM_DEVICE_FILE_EXT)) gpu.drmFile = drm;
    out.push_back(gpu);
  }
  return out;
}

}  // namespace

const Api* api(std::string* why) {
  static std::once_flag once;
  static Loaded loaded;
  std::call_once(once, [] { loaded = load(); });
  if (!loaded.why.empty()) {
    if (why) *why = loaded.why;
    return nullptr;
  }
  return &loaded.api;
}

std::vector<Gpu> visibleGpus(const Api& egl, std::string* problem) {
  std::vector<Gpu> all = machineGpus(egl);
  const char* list = std::getenv(kVisibleGpusVariable);
  if (!list || !*list) return all;
  std::vector<long> indices;
  std::stringstream items(list);
  std::string item;
  while (std::getline(items, item, ',')) {
    char* end = nullptr;
    const long index = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || index < 0) {
      if (problem)
        *problem = std::string(kVisibleGpusVariable) + "=" + list + ": expected GPU indices separated by commas, found '" +
                   item + "'";
      return {};
    }
    indices.push_back(index);
  }
  std::vector<Gpu> visible;
  for (const long index : indices) {
    if (size_t(index) >= all.size()) {
      if (problem)
        *problem = std::string(kVisibleGpusVariable) + "=" + list + " names GPU " + std::to_string(index) +
                   "; this machine has " + std::to_string(all.size()) + " GPU device(s), numbered from 0";
      return {};
    }
    visible.push_back(all[size_t(index)]);
  }
  return visible;
}

std::string describe(const Gpu& gpu, int visibleIndex) {
  std::string text = "EGL device " + std::to_string(gpu.machineIndex);
  if (gpu.machineIndex != visibleIndex) text += " (visible as " + std::to_string(visibleIndex) + ")";
  if (!gpu.drmFile.empty()) text += " (" + gpu.drmFile + ")";
  return text;
}

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  const std::string all = std::string(" ") + list + " ";
  return all.find(std::string(" ") + name + " ") != std::string::npos;
}

std::string hexError(EGLint error) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%04X", unsigned(error));
  return text;
}

}  // namespace sdg::egl
