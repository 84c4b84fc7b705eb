// The Isaac layer's Gf arithmetic in C++ (gf_quat, gf_product, ...): see below.
#include <pybind11/pybind11.h>

#include <cmath>
#include <initializer_list>

#include "scripting/script_bindings.h"

namespace py = pybind11;

namespace sdg::scripting {

// --- Gf fast paths for the Isaac layer (isaac_compat/pxr/Gf.py) ---------------
// Gf.Rotation's arithmetic as Gf.py computes it, with the same double
// operations in the same order, so the results are bit-identical: no FMA (the
// x86-64 build targets none), libm's sqrt, sin, cos, acos and atan2 as
// Python's math module calls them, math.radians/degrees as products by the same
// constants. Scripts build, multiply and decompose rotations per prim per
// frame; in Python that was most of a frame. Raw METH_FASTCALL functions:
// pybind11's dispatch would cost as much as the arithmetic. Each returns None
// where Python's math could raise or meet a non-finite value (Gf.py then
// computes it itself, as it does without this module); tests/python
// check_isaac_gf_native.py compares the two paths.
namespace gf_fast {

struct Unsure {};  // outside what is checked to match Python: Gf.py computes it

constexpr double kPi = 3.14159265358979323846;  // Py_MATH_PI
constexpr double kDegToRad = kPi / 180.0;         // math.radians(x) = x * degToRad
constexpr double kRadToDeg = 180.0 / kPi;         // math.degrees(x) = x * radToDeg

double root(double x) {
  if (!(x >= 0.0) || !std::isfinite(x)) throw Unsure{};
  return std::sqrt(x);
}

double angleOf(double y, double x) {
  if (!std::isfinite(y) || !std::isfinite(x)) throw Unsure{};
  return std::atan2(y, x);
}

// Python's max(-1.0, min(1.0, w)) (w is finite).
double clampUnit(double w) {
  double m = w < 1.0 ? w : 1.0;
  return m > -1.0 ? m : -1.0;
}

struct V3 { double x, y, z; };
struct Q4 { double w, x, y, z; };

V3 unit3(V3 v) {  // Vec3d.GetNormalized()
  double n = root(v.x * v.x + v.y * v.y + v.z * v.z);
  if (n > 1e-10) return {v.x / n, v.y / n, v.z / n};
  return {v.x / 1e-10, v.y / 1e-10, v.z / 1e-10};
}

Q4 unit4(Q4 q) {  // Quatd.GetNormalized()
  double n = root(q.w * q.w + (q.x * q.x + q.y * q.y + q.z * q.z));
  if (n < 1e-10) return {1.0, 0.0, 0.0, 0.0};
  return {q.w / n, q.x / n, q.y / n, q.z / n};
}

Q4 quatOf(V3 axis, double angle) {  // Rotation.GetQuat()
  double r = angle * kDegToRad / 2.0;
  double s = std::sin(r);
  double c = std::cos(r);
  return unit4({c, axis.x * s, axis.y * s, axis.z * s});
}

struct AxisAngle { V3 axis; double angle; };

AxisAngle axisAngleOf(Q4 q, V3 degenerate) {  // the tail of Rotation.__mul__
  double n = root(q.x * q.x + q.y * q.y + q.z * q.z);
  if (n > 1e-10) return {{q.x / n, q.y / n, q.z / n}, 2.0 * (std::acos(clampUnit(q.w)) * kRadToDeg)};
  return {degenerate, 0.0};
}

bool readFloats(PyObject* const* args, Py_ssize_t nargs, Py_ssize_t want, double* out) {
  if (nargs != want) return false;
  for (Py_ssize_t i = 0; i < want; ++i) {
    if (!PyFloat_CheckExact(args[i])) return false;
    out[i] = PyFloat_AS_DOUBLE(args[i]);
    if (!std::isfinite(out[i])) return false;
  }
  return true;
}

PyObject* tupleOf(std::initializer_list<double> values) {
  PyObject* t = PyTuple_New(Py_ssize_t(values.size()));
  if (!t) return nullptr;
  Py_ssize_t i = 0;
  for (double v : values) {
    PyObject* f = PyFloat_FromDouble(v);
    if (!f) { Py_DECREF(t); return nullptr; }
    PyTuple_SET_ITEM(t, i++, f);
  }
  return t;
}

// gf_quat(ax, ay, az, angle) -> (w, x, y, z): Rotation.GetQuat().
PyObject* quat(PyObject*, PyObject* const* args, Py_ssize_t nargs) {
  double a[4];
  if (!readFloats(args, nargs, 4, a)) Py_RETURN_NONE;
  try {
    Q4 q = quatOf({a[0], a[1], a[2]}, a[3]);
    return tupleOf({q.w, q.x, q.y, q.z});
  } catch (const Unsure&) { Py_RETURN_NONE; }
}

// gf_product(ax, ay, az, angle, bx, by, bz, angle_b) -> (x, y, z, angle):
// Rotation(a) * Rotation(b), a applied first.
PyObject* product(PyObject*, PyObject* const* args, Py_ssize_t nargs) {
  double a[8];
  if (!readFloats(args, nargs, 8, a)) Py_RETURN_NONE;
  try {
    V3 self{a[0], a[1], a[2]};
    Q4 q1 = quatOf({a[4], a[5], a[6]}, a[7]);  // the other's, as Gf.py: o.GetQuat() * self.GetQuat()
    Q4 q2 = quatOf(self, a[3]);
    Q4 q = unit4({q1.w * q2.w - q1.x * q2.x - q1.y * q2.y - q1.z * q2.z,
                  q1.w * q2.x + q1.x * q2.w + q1.y * q2.z - q1.z * q2.y,
                  q1.w * q2.y - q1.x * q2.z + q1.y * q2.w + q1.z * q2.x,
                  q1.w * q2.z + q1.x * q2.y - q1.y * q2.x + q1.z * q2.w});
    AxisAngle r = axisAngleOf(q, self);
    return tupleOf({r.axis.x, r.axis.y, r.axis.z, r.angle});
  } catch (const Unsure&) { Py_RETURN_NONE; }
}

// gf_decompose(ax, ay, az, angle, 3 x (x, y, z) axes) -> three angles in degrees:
// Rotation.Decompose(axis0, axis1, axis2); the matrix products are the sums
// Python's sum() makes, 0.0 + a + b + c.
PyObject* decompose(PyObject*, PyObject* const* args, Py_ssize_t nargs) {
  double a[13];
  if (!readFloats(args, nargs, 13, a)) Py_RETURN_NONE;
  try {
    Q4 q = quatOf({a[0], a[1], a[2]}, a[3]);
    const double w = q.w, x = q.x, y = q.y, z = q.z;
    const double a00 = 1 - 2 * (y * y + z * z), a01 = 2 * (x * y + z * w), a02 = 2 * (z * x - y * w);
    const double a10 = 2 * (x * y - z * w), a11 = 1 - 2 * (z * z + x * x), a12 = 2 * (y * z + x * w);
    const double a20 = 2 * (z * x + y * w), a21 = 2 * (y * z - x * w), a22 = 1 - 2 * (y * y + x * x);
    V3 n0 = unit3({a[4], a[5], a[6]}), n1 = unit3({a[7], a[8], a[9]}), n2 = unit3({a[10], a[11], a[12]});
    const double b00 = n0.x, b01 = n1.x, b02 = n2.x;
    const double b10 = n0.y, b11 = n1.y, b12 = n2.y;
    const double b20 = n0.z, b21 = n1.z, b22 = n2.z;
    const double t00 = 0.0 + b00 * a00 + b10 * a10 + b20 * a20;
    const double t01 = 0.0 + b00 * a01 + b10 * a11 + b20 * a21;
    const double t02 = 0.0 + b00 * a02 + b10 * a12 + b20 * a22;
    const double t10 = 0.0 + b01 * a00 + b11 * a10 + b21 * a20;
    const double t11 = 0.0 + b01 * a01 + b11 * a11 + b21 * a21;
    const double t12 = 0.0 + b01 * a02 + b11 * a12 + b21 * a22;
    const double t20 = 0.0 + b02 * a00 + b12 * a10 + b22 * a20;
    const double t21 = 0.0 + b02 * a01 + b12 * a11 + b22 * a21;
    const double t22 = 0.0 + b02 * a02 + b12 * a12 + b22 * a22;
    const double m00 = 0.0 + t00 * b00 + t01 * b10 + t02 * b20;
    const double m10 = 0.0 + t10 * b00 + t11 * b10 + t12 * b20;
    const double m20 = 0.0 + t20 * b00 + t21 * b10 + t22 * b20;
    const double m21 = 0.0 + t20 * b01 + t21 * b11 + t22 * b21;
    const double m22 = 0.0 + t20 * b02 + t21 * b12 + t22 * b22;
    const double cy = root(m00 * m00 + m10 * m10);
    double r0, r1, r2;
    if (cy > 1e-6) {
      r0 = angleOf(m21, m22), r1 = angleOf(-m20, cy), r2 = angleOf(m10, m00);
    } else {
      const double m11 = 0.0 + t10 * b01 + t11 * b11 + t12 * b21;
      const double m12 = 0.0 + t10 * b02 + t11 * b12 + t12 * b22;
      r0 = angleOf(-m12, m11), r1 = angleOf(-m20, cy), r2 = 0.0;
    }
    const double c0 = n0.y * n1.z - n0.z * n1.y, c1 = n0.z * n1.x - n0.x * n1.z, c2 = n0.x * n1.y - n0.y * n1.x;
    if (c0 * n2.x + c1 * n2.y + c2 * n2.z >= 0.0) r0 = -r0, r1 = -r1, r2 = -r2;
    return tupleOf({r0 * kRadToDeg, r1 * kRadToDeg, r2 * kRadToDeg});
  } catch (const Unsure&) { Py_RETURN_NONE; }
}

// gf_look_at(eye, center, up as 9 floats) -> Matrix4d.SetLookAt's rows (four lists of four floats).
PyObject* lookAt(PyObject*, PyObject* const* args, Py_ssize_t nargs) {
  double a[9];
  if (!readFloats(args, nargs, 9, a)) Py_RETURN_NONE;
  try {
    const double ex = a[0], ey = a[1], ez = a[2], ux = a[6], uy = a[7], uz = a[8];
    V3 v = unit3({a[3] - ex, a[4] - ey, a[5] - ez});
    V3 r = unit3({v.y * uz - v.z * uy, v.z * ux - v.x * uz, v.x * uy - v.y * ux});
    V3 p = unit3({r.y * v.z - r.z * v.y, r.z * v.x - r.x * v.z, r.x * v.y - r.y * v.x});
    const double rot[4][4] = {{r.x, p.x, -v.x, 0.0}, {r.y, p.y, -v.y, 0.0}, {r.z, p.z, -v.z, 0.0}, {0.0, 0.0, 0.0, 1.0}};
    const double tr[4][4] = {{1.0, 0.0, 0.0, 0.0}, {0.0, 1.0, 0.0, 0.0}, {0.0, 0.0, 1.0, 0.0}, {-ex, -ey, -ez, 1.0}};
    double m[16];
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        m[i * 4 + j] = tr[i][0] * rot[0][j] + tr[i][1] * rot[1][j] + tr[i][2] * rot[2][j] + tr[i][3] * rot[3][j];
    for (double x : m)
      if (!std::isfinite(x)) Py_RETURN_NONE;
    PyObject* rows = PyList_New(4);
    if (!rows) return nullptr;
    for (int i = 0; i < 4; ++i) {
      PyObject* row = PyList_New(4);
      if (!row) { Py_DECREF(rows); return nullptr; }
      PyList_SET_ITEM(rows, i, row);
      for (int j = 0; j < 4; ++j) {
        PyObject* f = PyFloat_FromDouble(m[i * 4 + j]);
        if (!f) { Py_DECREF(rows); return nullptr; }
        PyList_SET_ITEM(row, j, f);
      }
    }
    return rows;
  } catch (const Unsure&) { Py_RETURN_NONE; }
}

// gf_rotation_of(the 3x3 block's 9 floats, row by row) -> (x, y, z, angle): Matrix4d.ExtractRotation().
PyObject* rotationOf(PyObject*, PyObject* const* args, Py_ssize_t nargs) {
  double a[9];
  if (!readFloats(args, nargs, 9, a)) Py_RETURN_NONE;
  try {
    V3 r0 = unit3({a[0], a[1], a[2]}), r1 = unit3({a[3], a[4], a[5]}), r2 = unit3({a[6], a[7], a[8]});
    const double m00 = r0.x, m01 = r0.y, m02 = r0.z, m10 = r1.x, m11 = r1.y, m12 = r1.z, m20 = r2.x, m21 = r2.y,
                 m22 = r2.z;
    const double tr = m00 + m11 + m22;
    double w, x, y, z, s;
    if (tr > 0) {
      s = root(tr + 1.0) * 2;
      w = 0.25 * s, x = (m12 - m21) / s, y = (m20 - m02) / s, z = (m01 - m10) / s;
    } else if (m00 > m11 && m00 > m22) {
      s = root(1.0 + m00 - m11 - m22) * 2;
      w = (m12 - m21) / s, x = 0.25 * s, y = (m10 + m01) / s, z = (m20 + m02) / s;
    } else if (m11 > m22) {
      s = root(1.0 + m11 - m00 - m22) * 2;
      w = (m20 - m02) / s, x = (m10 + m01) / s, y = 0.25 * s, z = (m21 + m12) / s;
    } else {
      s = root(1.0 + m22 - m00 - m11) * 2;
      w = (m01 - m10) / s, x = (m20 + m02) / s, y = (m21 + m12) / s, z = 0.25 * s;
    }
    Q4 q = unit4({w, x, y, z});
    if (!(q.w >= 0)) q = {q.w * -1.0, q.x * -1.0, q.y * -1.0, q.z * -1.0};
    // Rotation.SetQuat
    const double n = root(q.x * q.x + q.y * q.y + q.z * q.z);
    if (n > 1e-10)
      return tupleOf({q.x / n, q.y / n, q.z / n,
                      2.0 * (std::acos(clampUnit(q.w / root(q.w * q.w + (q.x * q.x + q.y * q.y + q.z * q.z))))
                             * kRadToDeg)});
    return tupleOf({1.0, 0.0, 0.0, 0.0});
  } catch (const Unsure&) { Py_RETURN_NONE; }
}

PyMethodDef methods[] = {
    {"gf_quat", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&quat)), METH_FASTCALL,
     "Gf.Rotation.GetQuat of (axis x, y, z, angle): (w, x, y, z), or None."},
    {"gf_product", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&product)), METH_FASTCALL,
     "Gf.Rotation a * b of two (axis x, y, z, angle): (x, y, z, angle), or None."},
    {"gf_decompose", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&decompose)), METH_FASTCALL,
     "Gf.Rotation.Decompose of (axis x, y, z, angle) on three axes: three angles, or None."},
    {"gf_look_at", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&lookAt)), METH_FASTCALL,
     "Gf.Matrix4d.SetLookAt of (eye, center, up): its four rows, or None."},
    {"gf_rotation_of", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&rotationOf)), METH_FASTCALL,
     "Gf.Matrix4d.ExtractRotation of a 3x3 block: (x, y, z, angle), or None."},
    {nullptr, nullptr, 0, nullptr}};

void add(py::module_& m) {
  for (PyMethodDef* def = methods; def->ml_name; ++def) {
    PyObject* f = PyCFunction_NewEx(def, nullptr, nullptr);
    if (!f) throw py::error_already_set();
    m.add_object(def->ml_name, py::reinterpret_steal<py::object>(f));
  }
}

}  // namespace gf_fast

void bindGfFast(py::module_& m) { gf_fast::add(m); }

}  // namespace sdg::scripting
