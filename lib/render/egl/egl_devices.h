#pragma once
// libEGL and its GPU devices, for every GL context sdgbehave makes (the
// rasterizer's 3.3 context, the GPU path tracer's 4.x compute context), so
// that which GPU a process draws on is decided in one place.
//
// libEGL is opened once per process with dlopen (a machine without it gets
// a clear message, never a link error) and stays loaded: drivers keep
// process-lifetime state. GPUs come from EGL's device platform
// (EGL_EXT_device_enumeration + EGL_EXT_platform_device) in EGL's order,
// Mesa's software device left out (the surfaceless platform covers it).
// SDGBEHAVE_VISIBLE_GPUS="2,3" restricts a process to those devices (indices
// into that order), renumbered from 0 as CUDA_VISIBLE_DEVICES does, so `--gpu
// 0` in a process that sees "2,3" draws on the machine's third GPU.
#include <string>
#include <vector>

#include <EGL/egl.h>
#include <EGL/eglext.h>

namespace sdg::egl {

struct Api {
  PFNEGLGETPROCADDRESSPROC getProcAddress = nullptr;
  PFNEGLINITIALIZEPROC initialize = nullptr;
  PFNEGLBINDAPIPROC bindApi = nullptr;
  PFNEGLCHOOSECONFIGPROC chooseConfig = nullptr;
  PFNEGLCREATECONTEXTPROC createContext = nullptr;
  PFNEGLDESTROYCONTEXTPROC destroyContext = nullptr;
  PFNEGLMAKECURRENTPROC makeCurrent = nullptr;
  PFNEGLGETERRORPROC getError = nullptr;
  PFNEGLQUERYSTRINGPROC queryString = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay = nullptr;
  PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;            // optional
  PFNEGLQUERYDEVICESTRINGEXTPROC queryDeviceString = nullptr;  // optional
};

// libEGL's functions, loaded on first use; null when it cannot be (then
// `why` says why: no libEGL.so.1, or a function it lacks).
const Api* api(std::string* why = nullptr);

// The environment variable restricting a process to some GPUs.
inline constexpr const char* kVisibleGpusVariable = "SDGBEHAVE_VISIBLE_GPUS";

struct Gpu {
  EGLDeviceEXT device = nullptr;
  int machineIndex = 0;  // its place among all of the machine's GPUs
  std::string drmFile;   // "/dev/dri/card1", when EGL says
};

// The GPUs this process may use, in order (index = what --gpu names). A
// malformed SDGBEHAVE_VISIBLE_GPUS, or one naming a GPU the machine lacks,
// sets `problem` and gives none.
std::vector<Gpu> visibleGpus(const Api& egl, std::string* problem = nullptr);

// "EGL device 1 (/dev/dri/card2)", or "... of the machine's, visible as 0" when restricted.
std::string describe(const Gpu& gpu, int visibleIndex);

// True when the extension list `list` names `name`.
bool hasExtension(const char* list, const char* name);
// An EGL error code as 0x3001.
std::string hexError(EGLint error);

}  // namespace sdg::egl
