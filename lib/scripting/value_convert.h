#pragma once
// Values between the stage and Python: vectors as tuples, quaternions as
// (w, x, y, z), matrices as four row tuples in USD's row-vector layout,
// float attributes through their shortest text (0.9f reads as 0.9).
// Writing checks the Python value against the attribute's type; a mismatch
// raises TypeError/ValueError saying what was expected and found.
#include <string>

#include <pybind11/pybind11.h>

#include "stage/value.h"

namespace sdg::scripting {

pybind11::object toPython(const Value& value);
// `what` names the target in messages ("/Root/Box.size").
Value fromPython(pybind11::handle object, ValueType type, const std::string& what);

// Vectors and 3x3 matrices (nested sequences, numpy arrays included).
Vec3d vec3FromPython(pybind11::handle object, const std::string& what);
Matrix3d matrix3FromPython(pybind11::handle object, const std::string& what);
pybind11::tuple vec3ToPython(const Vec3d& v);
pybind11::tuple matrix3ToPython(const Matrix3d& m);

}  // namespace sdg::scripting
