// The `_sdgbehave` module's driver side: `driver()`, the handle a driver
// program (`sdgbehave exec`) has on the run executing it (driver_host.h),
// and runDriverProgram, which runs such a program.
#include "scripting/script_driver.h"

#include <pybind11/embed.h>
#include <pybind11/stl.h>

#include "core/diagnostics.h"
#include "scripting/driver_host.h"
#include "scripting/python_host.h"
#include "scripting/script_call.h"
#include "scripting/script_context.h"

namespace py = pybind11;

namespace sdg::scripting {
namespace {

DriverHost* gHost = nullptr;

DriverHost& host() {
  if (!gHost) throw py::value_error("no driver program runs: the Isaac Sim app's APIs work under `sdgbehave exec`");
  return *gHost;
}

// A SceneError or RunError from the run, as the ValueError/RuntimeError a
// program's traceback locates at its own line.
template <typename Call>
auto translated(Call&& call) {
  try {
    return call();
  } catch (const SceneError& e) {
    throw py::value_error(e.what());
  }
}

nlohmann::json jsonFromPython(py::handle o) {
  py::module_ json = py::module_::import("json");
  return nlohmann::json::parse(py::str(json.attr("dumps")(o)).cast<std::string>());
}

}  // namespace

void setDriverHost(DriverHost* host) { gHost = host; }
DriverHost* driverHost() { return gHost; }

void bindDriver(py::module_& m) {
  struct Driver {};
  py::class_<Driver>(m, "Driver", "The run executing a driver program (sdgbehave exec).")
      .def_property_readonly("context", [](Driver&) { return host().context(); })
      .def("new_stage", [](Driver&) { translated([] { host().newStage(); }); })
      .def("open_stage", [](Driver&, const std::string& path) { translated([&] { host().openStage(path); }); })
      .def("save_stage", [](Driver&, const std::string& path) { translated([&] { host().saveStage(path); }); })
      .def("reference", [](Driver&, const std::string& prim, const std::string& file) {
        translated([&] { host().reference(prim, file); });
      })
      .def("move_prim", [](Driver&, const std::string& from, const std::string& to) {
        translated([&] { host().movePrim(from, to); });
      })
      .def_property_readonly("assets_root", [](Driver&) { return host().assetsRoot(); })
      .def("update", [](Driver&) { translated([] { host().update(); }); })
      .def("play", [](Driver&) { translated([] { host().play(); }); })
      .def("pause", [](Driver&) { translated([] { host().pause(); }); })
      .def("stop", [](Driver&) { translated([] { host().stop(); }); })
      .def_property_readonly("playing", [](Driver&) { return host().playing(); })
      .def_property_readonly("time", [](Driver&) { return host().time(); })
      .def_property_readonly("time_codes_per_second", [](Driver&) { return host().timeCodesPerSecond(); })
      .def("set_seed", [](Driver&, int64_t seed) { host().setSeed(seed); })
      .def("attach_writer",
           [](Driver&, const std::string& outDir, py::handle options, std::vector<std::string> cameras, int width,
              int height) {
             nlohmann::json o = jsonFromPython(options);
             return translated([&] { return host().attachWriter(outDir, o, cameras, width, height); });
           })
      .def("capture", [](Driver&) { translated([] { host().capture(); }); })
      .def("detach_writer", [](Driver&, int id) { translated([&] { host().detachWriter(id); }); })
      .def_property_readonly("attached_writers", [](Driver&) { return host().attachedWriters(); });
  m.def("driver", []() -> py::object { return gHost ? py::cast(Driver{}) : py::object(py::none()); },
        "The run executing the driver program, or None outside `sdgbehave exec`.");
}

void runDriverProgram(const std::string& absolute, const std::string& path, const std::vector<std::string>& args) {
  PythonHost& python = PythonHost::instance();
  python.addScriptFile(absolute, path);
  try {
    python.api().attr("_run_program")(absolute, args);
  } catch (py::error_already_set& e) {
    const std::string exit = exitCall(e);
    if (exit == "sys.exit(0)" || exit == "sys.exit()") return;  // the program ended itself, successfully
    PythonHost::ErrorInfo info = python.describe(e);
    const std::string where = info.loc.known() ? info.loc.str() : path;
    throw RunError(where + ": the program failed" + (exit.empty() ? "" : " (it called " + exit + ")") + ":\n" +
                   info.text);
  }
}

}  // namespace sdg::scripting
