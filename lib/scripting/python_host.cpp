#include "scripting/python_host.h"

#include <atomic>
#include <map>
#include <mutex>

#include <pybind11/embed.h>

#include "core/diagnostics.h"
#include "scripting/hook_watchdog.h"

namespace py = pybind11;

// sdgbehave.py, embedded at build time (see lib/CMakeLists.txt).
extern const char kSdgbehavePySource[];
// The native module `_sdgbehave` (script_api.cpp). Registered here by name:
// pybind11's static self-registration lives in an object file nothing else
// references, which the linker may leave out of the binary.
extern "C" PyObject* pybind11_init_impl__sdgbehave();
// The Isaac Sim layer's modules (lib/scripting/isaac_compat), embedded by
// embed_package.cmake.
struct SdgEmbeddedFile {
  const char* path;
  const char* source;
};
extern const SdgEmbeddedFile kIsaacCompatFiles[];
extern const size_t kIsaacCompatFilesCount;

namespace sdg::scripting {
namespace {
std::atomic<bool> gStarted = false;
std::atomic<PyThreadState*> gScriptThread = nullptr;
pthread_t gScriptThreadId;

// The scripts' paths, absolute -> shown, for threads that cannot touch
// Python objects (the watchdog, the signal handler's thread).
std::mutex gPathsMutex;
std::map<std::string, std::string>& shownPaths() {
  static auto* paths = new std::map<std::string, std::string>();
  return *paths;
}
}  // namespace

bool PythonHost::started() { return gStarted; }

std::string shownScriptPath(const std::string& path) {
  std::lock_guard lock(gPathsMutex);
  auto it = shownPaths().find(path);
  return it == shownPaths().end() ? path : it->second;
}

bool isScriptPath(const std::string& path) {
  std::lock_guard lock(gPathsMutex);
  return shownPaths().count(path) != 0;
}

PythonHost& PythonHost::instance() {
  // Never destroyed: the interpreter outlives every object that refers to it.
  static PythonHost* host = new PythonHost();
  return *host;
}

PythonHost::PythonHost() {
  if (PyImport_AppendInittab("_sdgbehave", &pybind11_init_impl__sdgbehave) != 0)
    throw std::runtime_error("cannot register the _sdgbehave module");
#if defined(__SANITIZE_ADDRESS__)
  // Under AddressSanitizer, Python allocates with malloc instead of its own
  // arenas: LeakSanitizer then sees what Python objects point to (OpenSSL
  // state held by hashlib, say) instead of calling it leaked, and ASan
  // checks the memory of the objects the bindings touch.
  PyPreConfig preconfig;
  PyPreConfig_InitIsolatedConfig(&preconfig);
  preconfig.allocator = PYMEM_ALLOCATOR_MALLOC;
  if (PyStatus status = Py_PreInitialize(&preconfig); PyStatus_Exception(status))
    throw std::runtime_error(status.err_msg ? status.err_msg : "cannot pre-initialize Python");
#endif
  PyConfig config;
  PyConfig_InitIsolatedConfig(&config);
  config.use_hash_seed = 1;
  config.hash_seed = 0;
  config.buffered_stdio = 0;
  config.install_signal_handlers = 0;  // Ctrl-C stays sdgbehave's (and the OS's)
  config.parse_argv = 0;
  py::initialize_interpreter(&config, 0, nullptr, /*add_program_dir_to_path=*/false);
  gStarted = true;

  py::module_ sys = py::module_::import("sys");
  sys.attr("stdout") = sys.attr("stderr");
  sys.attr("dont_write_bytecode") = true;  // never write __pycache__ into a user's script folder

  // The pure-Python half of the API, compiled under its own name so that
  // tracebacks through it read "sdgbehave.py".
  py::module_ types = py::module_::import("types");
  api_ = types.attr("ModuleType")("sdgbehave");
  api_.attr("__file__") = "sdgbehave.py";
  sys.attr("modules")["sdgbehave"] = api_;
  py::module_ builtins = py::module_::import("builtins");
  py::object code =
      builtins.attr("compile")(py::str(static_cast<const char*>(kSdgbehavePySource)), "sdgbehave.py", "exec");
  builtins.attr("exec")(code, api_.attr("__dict__"));
  scriptFiles_ = py::dict();
  scriptExit_ = api_.attr("ScriptExit");
  gScriptThreadId = pthread_self();
  gScriptThread = PyThreadState_Get();
  api_.attr("_install_watchdog_signal")(watchdogSignal());
  py::dict embedded;
  for (size_t i = 0; i < kIsaacCompatFilesCount; ++i)
    embedded[py::str(kIsaacCompatFiles[i].path)] = py::str(kIsaacCompatFiles[i].source);
  api_.attr("_install_embedded")(embedded);
}

PyThreadState* scriptThreadState() { return gScriptThread; }
pthread_t scriptThread() { return gScriptThreadId; }

void PythonHost::addScriptFile(const std::string& absolutePath, const std::string& shownPath) {
  scriptFiles_[py::str(absolutePath)] = py::str(shownPath);
  std::lock_guard lock(gPathsMutex);
  shownPaths()[absolutePath] = shownPath;
}

PythonHost::ErrorInfo PythonHost::describe(py::error_already_set& error) {
  py::tuple where = api_.attr("_error_location")(error.value(), error.trace(), scriptFiles_);
  ErrorInfo info;
  std::string file = where[0].cast<std::string>();
  if (!file.empty()) info.loc = SourceLoc{file, where[1].cast<int>(), where[2].cast<int>()};
  info.text = where[3].cast<std::string>();
  return info;
}

void PythonHost::seedGlobalRandom(uint64_t seed) { api_.attr("_seed_global_random")(seed); }

}  // namespace sdg::scripting
