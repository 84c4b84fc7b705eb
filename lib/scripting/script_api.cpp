// The native half of the `sdgbehave` Python module (`_sdgbehave`): the module
// itself, the log and look-at functions and Rng; each other type has its own
// binding file (script_bindings.h): Prim (script_prim_binding.cpp), Stage and
// Context (script_stage_binding.cpp), the Isaac layer's Gf arithmetic
// (script_gf_fast.cpp), PhysicsWorld (script_physics.cpp), Driver
// (script_driver.cpp).
#include <pybind11/embed.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <optional>
#include <stdexcept>

#include "behavior/rng.h"
#include "core/log.h"
#include "scripting/hook_watchdog.h"
#include "scripting/script_bindings.h"
#include "scripting/script_driver.h"
#include "scripting/script_physics.h"
#include "scripting/value_convert.h"
#include "stage/look_at.h"

namespace py = pybind11;

namespace sdg::scripting {

Stage& ScriptContext::liveStage() const {
  if (!stage) throw std::runtime_error(primPath + ": the behavior has been destroyed; its handles no longer work");
  return *stage;
}

Rng& ScriptContext::randomStream() {
  if (!rngReady) {
    int32_t fixedSeed = -1;
    if (const AttributeSpec* seed = spec->findVariable("seed"); seed && seed->type == ValueType::Int)
      if (const Prim* p = liveStage().find(primPath))
        if (const Value* v = p->value(exposedAttributeName(spec->name, "seed"))) fixedSeed = v->get<int32_t>();
    rng = makeBehaviorRng(runSeed, primPath, rngStream, iteration, fixedSeed);
    rngReady = true;
  }
  return rng;
}

PYBIND11_EMBEDDED_MODULE(_sdgbehave, m) {
  m.doc() = "The native half of sdgbehave's script API; import sdgbehave instead.";
  bindGfFast(m);  // the Isaac layer's Gf arithmetic (gf_quat, gf_product, ...)

  m.def("log", [](const std::string& level, const std::string& message) {
    if (level == "debug") log::debug(message);
    else if (level == "warning") log::warn(message);
    else if (level == "error") log::error(message);
    else log::info(message);
  });

  // The watchdog's side (sdgbehave._on_hook_timeout), not part of the API.
  m.def("_hook_interrupted", &takeInterruption);
  m.def("_hook_timeout", &hookTimeout);

  m.def("look_at_rotation",
        [](py::handle eye, py::handle target, py::handle up) -> py::object {
          std::optional<Matrix3d> r = lookAtRotation(vec3FromPython(eye, "look_at_rotation eye"),
                                                     vec3FromPython(target, "look_at_rotation target"),
                                                     vec3FromPython(up, "look_at_rotation up"));
          return r ? py::object(matrix3ToPython(*r)) : py::object(py::none());
        },
        py::arg("eye"), py::arg("target"), py::arg("up") = py::make_tuple(0.0, 0.0, 1.0),
        "The world rotation (3x3, rows) that aims a prim's -Z from eye at target with +Y toward up; None when "
        "eye == target.");

  bindPhysics(m);
  bindDriver(m);
  py::class_<Rng>(m, "Rng", "A portable random stream (PCG32): the same draws on every machine.")
      .def("random", &Rng::uniform01, "A float in [0, 1).")
      .def("uniform", &Rng::uniform, py::arg("low") = 0.0, py::arg("high") = 1.0, "low + (high - low) * random().")
      .def("integers",
           [](Rng& r, int64_t low, int64_t high) {
             if (high <= low) throw py::value_error("integers: high must exceed low");
             return r.integers(low, high);
           },
           py::arg("low"), py::arg("high"), "An int in [low, high), unbiased.")
      .def("normal",
           [](Rng& r, double mean, double stddev) {
             // Marsaglia's polar method: uniform draws and sqrt/log only.
             double u, v, s;
             do {
               u = 2.0 * r.uniform01() - 1.0;
               v = 2.0 * r.uniform01() - 1.0;
               s = u * u + v * v;
             } while (s >= 1.0 || s == 0.0);
             return mean + stddev * u * std::sqrt(-2.0 * std::log(s) / s);
           },
           py::arg("mean") = 0.0, py::arg("stddev") = 1.0, "A normally distributed float.")
      .def("bernoulli", &Rng::bernoulli, py::arg("p"), "True with probability p.")
      .def("choice",
           [](Rng& r, const py::sequence& items) {
             if (items.size() == 0) throw py::value_error("choice: the sequence is empty");
             return items[r.index(items.size())];
           },
           py::arg("items"), "One element of a non-empty sequence.")
      .def("shuffle",
           [](Rng& r, py::list& items) {
             // Fisher-Yates from the end, one integers() draw per position.
             for (size_t i = items.size(); i > 1; --i) {
               size_t j = r.index(i);
               py::object a = items[i - 1], b = items[j];
               items[i - 1] = b;
               items[j] = a;
             }
           },
           py::arg("items"), "Shuffles a list in place.");
  bindPrim(m);
  bindStage(m);
  bindContext(m);
}

}  // namespace sdg::scripting
