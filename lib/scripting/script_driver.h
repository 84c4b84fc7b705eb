#pragma once
// The native module's `driver()` (driver_host.h says what it reaches).
#include <pybind11/pybind11.h>

namespace sdg::scripting {

// Adds `Driver` and `driver()` to the `_sdgbehave` module.
void bindDriver(pybind11::module_& m);

}  // namespace sdg::scripting
