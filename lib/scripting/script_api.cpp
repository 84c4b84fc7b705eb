// The native half of the `sdgbehave` Python module (`_sdgbehave`): Prim,
// Stage and Rng handles over the running stage. Every write goes through the
// behavior's journal first, so sdgbehave can undo it; transforms are written
// into the prim's existing xform ops exactly as the built-in behaviors write
// them (stage/xform_edit.h), so a script can reproduce a built-in bit for bit.
#include <pybind11/embed.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>

#include "assets/asset_resolver.h"
#include "behavior/behavior_prims.h"
#include "behavior/run_activity.h"
#include "core/log.h"
#include "core/text.h"
#include "scripting/script_physics.h"
#include "scripting/hook_watchdog.h"
#include "scripting/python_host.h"
#include "scripting/script_call.h"
#include "scripting/script_context.h"
#include "scripting/script_driver.h"
#include "scripting/value_convert.h"
#include "stage/look_at.h"
#include "stage/path.h"
#include "stage/prim_types.h"
#include "stage/xform_edit.h"

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

namespace {

using ContextPtr = std::shared_ptr<ScriptContext>;

// A prim by path: looked up on every call, so a handle never dangles.
struct PrimHandle {
  ContextPtr ctx;
  std::string path;

  Prim& prim() const {
    Prim* p = ctx->liveStage().find(path);
    if (!p) throw py::value_error("prim " + path + " no longer exists");
    return *p;
  }
  std::string what(const std::string& attribute) const { return path + "." + attribute; }
};

struct StageHandle {
  ContextPtr ctx;
};

// A Python list of exactly three floats (what a Gf.Vec3d is underneath), read
// with no allocation: Isaac scripts write a translate per prim per frame.
// Anything else goes through fromPython, which checks and names the error.
std::optional<Vec3d> exactFloatList3(py::handle o) {
  PyObject* list = o.ptr();
  if (!PyList_Check(list) || PyList_GET_SIZE(list) != 3) return std::nullopt;
  Vec3d v;
  for (Py_ssize_t i = 0; i < 3; ++i) {
    PyObject* x = PyList_GET_ITEM(list, i);
    if (!PyFloat_CheckExact(x)) return std::nullopt;
    v[int(i)] = PyFloat_AS_DOUBLE(x);
  }
  return v;
}

// A tuple of exactly four floats (w, x, y, z), read with no allocation: the
// Isaac layer writes a quaternion per prim per frame (Gf.Quatd's own floats).
std::optional<Quatd> exactFloatTuple4(py::handle o) {
  PyObject* tuple = o.ptr();
  if (!PyTuple_CheckExact(tuple) || PyTuple_GET_SIZE(tuple) != 4) return std::nullopt;
  double q[4];
  for (Py_ssize_t i = 0; i < 4; ++i) {
    PyObject* x = PyTuple_GET_ITEM(tuple, i);
    if (!PyFloat_CheckExact(x)) return std::nullopt;
    q[i] = PyFloat_AS_DOUBLE(x);
  }
  return Quatd(q[0], q[1], q[2], q[3]);
}

py::object handleOrNone(const ContextPtr& ctx, const Prim* p) {
  if (!p || p->isPseudoRoot()) return py::none();
  return py::cast(PrimHandle{ctx, p->path()});
}

// The type a write to `name` must have: the authored attribute's, else the
// schema's, else `declared` (creating a custom attribute).
std::pair<ValueType, const AttributeSpec*> targetType(const Prim& prim, const std::string& name,
                                                      const std::optional<std::string>& declared,
                                                      const std::string& what) {
  const AttributeSpec* schema = findSchemaAttribute(prim.type(), name);
  if (const Attribute* a = prim.findAttribute(name)) return {a->value.type(), schema};
  if (schema) return {schema->type, schema};
  if (!declared)
    throw py::value_error(what + ": the prim has no attribute '" + name +
                          "'; pass type= (a USD type name such as 'double' or 'color3f') to create a custom one");
  std::optional<ValueType> type = valueTypeFromName(*declared);
  if (!type) throw py::value_error(what + ": unknown type '" + *declared + "'");
  return {*type, nullptr};
}

void checkAgainstSpec(const AttributeSpec& spec, const Value& v, const std::string& what) {
  if (!spec.allowedTokens.empty()) {
    const std::string& token = v.get<std::string>();
    if (std::find(spec.allowedTokens.begin(), spec.allowedTokens.end(), token) == spec.allowedTokens.end())
      throw py::value_error(what + ": expected one of " + text::join(spec.allowedTokens, ", ") + ", found '" + token +
                            "'");
  }
  if (spec.minimum) {
    py::object o = toPython(v);
    auto check = [&](double x) {
      if (x < *spec.minimum)
        throw py::value_error(what + ": must be at least " + text::formatDouble(*spec.minimum) + ", found " +
                              text::formatDouble(x));
    };
    if (py::isinstance<py::tuple>(o))
      for (py::handle x : o) check(x.cast<double>());
    else if (py::isinstance<py::float_>(o) || py::isinstance<py::int_>(o))
      check(o.cast<double>());
  }
}

void setAttribute(PrimHandle& h, const std::string& name, py::handle value, std::optional<std::string> type) {
  Prim& prim = h.prim();
  if (parseXformOpName(name))
    throw py::value_error(h.what(name) + ": xform ops are written with set_location / set_rotation / set_scale");
  auto [valueType, schema] = targetType(prim, name, type, h.what(name));
  Value v = fromPython(value, valueType, h.what(name));
  if (schema) checkAgainstSpec(*schema, v, h.what(name));
  ScriptContext& ctx = *h.ctx;
  if (!ctx.created(prim)) ctx.journal().beforeAttributeWrite(prim, name);
  const Attribute* existing = prim.findAttribute(name);
  const bool custom = existing ? existing->custom : schema == nullptr;
  prim.setAttribute(name, std::move(v), custom);
}

// The op a write goes into, found (or inserted) as the built-ins do, after
// the journal saved the prim's ops.
XformOp& opToWrite(PrimHandle& h, std::optional<size_t> (*find)(const Prim&), size_t (*insert)(Prim&)) {
  Prim& prim = h.prim();
  if (!prim.typeInfo().xformable)
    throw py::value_error(h.path + " is a " + std::string(prim.typeInfo().name) + ", which has no transform");
  if (!h.ctx->created(prim)) h.ctx->journal().beforeXformWrite(prim);
  std::optional<size_t> index = find(prim);
  if (!index) index = insert(prim);
  return prim.xformOps()[*index];
}

XformOp& locationOp(PrimHandle& h) { return opToWrite(h, &findLocationOp, &insertTranslateOp); }
XformOp& rotationOp(PrimHandle& h) { return opToWrite(h, &findRotationOp, &insertOrientOp); }

Matrix4d parentWorld(const Stage& stage, const Prim& prim) {
  return prim.parent()->isPseudoRoot() ? Matrix4d::Identity() : stage.worldMatrix(*prim.parent());
}

py::tuple matrix4ToPython(const Matrix4d& m) {
  py::list rows;
  for (int r = 0; r < 4; ++r) rows.append(py::make_tuple(m(r, 0), m(r, 1), m(r, 2), m(r, 3)));
  return py::tuple(rows);
}

PrimHandle definePrim(StageHandle& s, const std::string& path, const std::string& typeName) {
  ScriptContext& ctx = *s.ctx;
  Stage& stage = ctx.liveStage();
  const std::string scope = std::string(kBehaviorsScope) + "/" + ctx.ns();
  if (!ctx.driver && !path.starts_with(scope + "/"))
    throw py::value_error("define_prim: " + ctx.ns() + " creates prims under " + scope + "/, not at " + path);
  if (std::string why = path::whyInvalid(path); !why.empty()) throw py::value_error("define_prim: " + path + ": " + why);
  if (stage.find(path)) throw py::value_error("define_prim: " + path + " already exists (see next_free_path)");
  std::optional<PrimType> type = primTypeFromName(typeName);
  if (!type) {
    std::vector<std::string> names;
    for (const PrimTypeInfo& info : allPrimTypes()) names.emplace_back(info.name);
    throw py::value_error("define_prim: unknown prim type '" + typeName + "'" + text::didYouMean(typeName, names));
  }
  // Missing ancestors become scopes; each is a prim this behavior created.
  std::vector<std::string> missing;
  for (std::string parent(path::parent(path)); parent.size() > 1 && !stage.find(parent);
       parent = std::string(path::parent(parent)))
    missing.push_back(parent);
  // (A driver's are its own: nothing undoes them.) USD's typeless ancestors are scopes here.
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    Prim& scope = stage.definePrim(*it, PrimType::Scope);
    if (!ctx.driver) ctx.journal().created(scope);
  }
  Prim& prim = stage.definePrim(path, *type);
  if (!ctx.driver) ctx.journal().created(prim);
  return PrimHandle{s.ctx, path};
}

void removePrim(StageHandle& s, const std::string& path) {
  ScriptContext& ctx = *s.ctx;
  Stage& stage = ctx.liveStage();
  Prim* prim = stage.find(path);
  if (!prim) throw py::value_error("remove_prim: " + path + " does not exist");
  if (!ctx.created(*prim)) throw py::value_error("remove_prim: " + path + " was not created by " + ctx.ns());
  // The journals key prims by address: forget the removed ones, so that a
  // prim created later at the same address is not taken for this one.
  for (Prim* p : stage.subtree(*prim)) {
    ctx.playJournal.forget(*p);
    ctx.idleJournal.forget(*p);
  }
  stage.removePrim(path);
}

std::vector<PrimHandle> traverse(StageHandle& s, py::object root) {
  Stage& stage = s.ctx->liveStage();
  Prim* start = &stage.pseudoRoot();
  if (!root.is_none()) start = &(root.cast<PrimHandle&>().prim());
  std::vector<PrimHandle> out;
  for (Prim* p : stage.subtree(*start))
    if (!p->isPseudoRoot()) out.push_back(PrimHandle{s.ctx, p->path()});
  return out;
}

py::dict payloadToPython(const Payload& payload) {
  py::dict d;
  for (const auto& [key, value] : payload.entries())
    std::visit([&](const auto& v) { d[py::str(key)] = py::cast(v); }, value);
  return d;
}

Payload payloadFromPython(const py::dict& d, const std::string& what) {
  Payload payload;
  for (auto [key, value] : d) {
    if (!py::isinstance<py::str>(key)) throw py::type_error(what + ": payload keys are strings");
    std::string k = key.cast<std::string>();
    if (py::isinstance<py::bool_>(value)) payload.set(k, value.cast<bool>());
    else if (py::isinstance<py::str>(value)) payload.set(k, value.cast<std::string>());
    else if (PyNumber_Check(value.ptr())) payload.set(k, value.cast<double>());
    else throw py::type_error(what + ": payload value '" + k + "' must be a str, number or bool, found " +
                              std::string(py::str(py::type::handle_of(value).attr("__name__"))));
  }
  return payload;
}


// The op named `name` ("xformOp:translate", ...) on the prim, or null.
// Whether `op` is the op attribute `name` ("xformOp:<kind>[:<suffix>]"),
// compared in place: scripts set ops per prim per frame.
bool isOpNamed(const XformOp& op, std::string_view name) {
  constexpr std::string_view kPrefix = "xformOp:";
  const std::string_view kind = xformOpKindName(op.kind);
  if (!name.starts_with(kPrefix)) return false;
  name.remove_prefix(kPrefix.size());
  if (!name.starts_with(kind)) return false;
  name.remove_prefix(kind.size());
  if (op.suffix.empty()) return name.empty();
  return name.size() == op.suffix.size() + 1 && name[0] == ':' && name.substr(1) == op.suffix;
}

XformOp* findOp(Prim& prim, std::string_view name) {
  for (XformOp& op : prim.xformOps())
    if (isOpNamed(op, name)) return &op;
  return nullptr;
}

// An op's starting value: identity for its kind.
Value identityOpValue(XformOpKind kind) {
  switch (xformOpValueType(kind)) {
    case ValueType::Quatd: return Value::makeQuatd(Quatd::Identity());
    case ValueType::Matrix4d: return Value::makeMatrix4d(Matrix4d::Identity());
    case ValueType::Double: return Value::makeDouble(0.0);
    default: return Value::makeDouble3(kind == XformOpKind::Scale ? Vec3d::Ones() : Vec3d::Zero());
  }
}

}  // namespace

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

PYBIND11_EMBEDDED_MODULE(_sdgbehave, m) {
  m.doc() = "The native half of sdgbehave's script API; import sdgbehave instead.";
  gf_fast::add(m);  // the Isaac layer's Gf arithmetic (gf_quat, gf_product, ...)

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

  py::class_<PrimHandle>(m, "Prim", "A prim of the stage, by path.")
      .def_property_readonly("path", [](const PrimHandle& h) { return h.path; })
      .def_property_readonly("name", [](const PrimHandle& h) { return std::string(h.prim().name()); })
      .def_property_readonly("type_name", [](const PrimHandle& h) { return std::string(h.prim().typeInfo().name); })
      .def_property_readonly("is_valid", [](const PrimHandle& h) { return h.ctx->stage && h.ctx->stage->find(h.path); })
      .def_property_readonly("is_xformable", [](const PrimHandle& h) { return h.prim().typeInfo().xformable; })
      .def_property_readonly("is_geometry", [](const PrimHandle& h) { return h.prim().typeInfo().gprim; })
      .def_property_readonly("is_light", [](const PrimHandle& h) { return h.prim().typeInfo().light; })
      .def_property_readonly("is_camera", [](const PrimHandle& h) { return h.prim().type() == PrimType::Camera; })
      .def_property_readonly("parent", [](const PrimHandle& h) { return handleOrNone(h.ctx, h.prim().parent()); })
      .def_property_readonly("children",
                             [](const PrimHandle& h) {
                               std::vector<PrimHandle> out;
                               for (const Prim* c : h.prim().children()) out.push_back(PrimHandle{h.ctx, c->path()});
                               return out;
                             })
      .def("get_attribute",
           [](const PrimHandle& h, const std::string& name) -> py::object {
             const Value* v = h.prim().value(name);
             return v ? toPython(*v) : py::object(py::none());
           },
           py::arg("name"), "The attribute's value (authored, else the schema's fallback), or None.")
      .def("has_attribute", [](const PrimHandle& h, const std::string& name) { return h.prim().value(name) != nullptr; },
           py::arg("name"))
      .def("attribute_names",
           [](const PrimHandle& h) {
             std::vector<std::string> names;
             for (const auto& [name, a] : h.prim().attributes()) names.push_back(name);
             return names;
           },
           "Names of the authored attributes, sorted.")
      .def("attribute_type",
           [](const PrimHandle& h, const std::string& name) -> py::object {
             Prim& p = h.prim();
             const Value* v = parseXformOpName(name) ? (findOp(p, name) ? &findOp(p, name)->value : nullptr)
                                                     : p.value(name);
             return v ? py::object(py::str(std::string(valueTypeName(v->type())))) : py::object(py::none());
           },
           py::arg("name"), "The USD type name of an attribute or xform op ('double3', 'quatd', ...), or None.")
      .def("set_xform_op",
           [](PrimHandle& h, std::string_view name, py::handle value) {
             Prim& p = h.prim();
             XformOp* op = findOp(p, name);
             if (!op) throw py::value_error(h.what(std::string(name)) + ": the prim has no such xform op");
             std::optional<Vec3d> fast =
                 op->value.type() == ValueType::Double3 ? exactFloatList3(value) : std::nullopt;
             std::optional<Quatd> quat =
                 op->value.type() == ValueType::Quatd ? exactFloatTuple4(value) : std::nullopt;
             Value v = fast   ? Value::makeDouble3(*fast)
                       : quat ? Value::makeQuatd(*quat)
                              : fromPython(value, op->value.type(), h.what(std::string(name)));
             // The journal copies the ops aside; `op` still points into the prim's.
             if (!h.ctx->created(p)) h.ctx->journal().beforeXformWrite(p);
             op->value = std::move(v);
           },
           py::arg("name"), py::arg("value"), "Writes one xform op's value, in the op's own type.")
      .def("add_xform_op",
           [](PrimHandle& h, const std::string& name) {
             Prim& p = h.prim();
             std::optional<XformOp> op = parseXformOpName(name);
             if (!op) throw py::value_error(h.what(name) + ": not an xform op name such as 'xformOp:translate'");
             if (!p.typeInfo().xformable)
               throw py::value_error(h.path + " is a " + std::string(p.typeInfo().name) + ", which has no transform");
             if (findOp(p, name)) throw py::value_error(h.what(name) + ": the op already exists");
             if (!h.ctx->created(p)) h.ctx->journal().beforeXformWrite(p);
             op->value = identityOpValue(op->kind);
             p.xformOps().push_back(std::move(*op));
           },
           py::arg("name"), "Appends an xform op (last in xformOpOrder) holding the identity.")
      .def("remove_attribute",
           [](PrimHandle& h, const std::string& name) {
             Prim& p = h.prim();
             if (parseXformOpName(name)) throw py::value_error(h.what(name) + ": xform ops cannot be removed");
             if (!p.findAttribute(name)) return false;
             if (!h.ctx->created(p)) h.ctx->journal().beforeAttributeWrite(p, name);
             return p.removeAttribute(name);
           },
           py::arg("name"), "Removes an authored attribute (restored on stop or destroy); False if absent.")
      .def("set_attribute", &setAttribute, py::arg("name"), py::arg("value"), py::arg("type") = py::none(),
           "Writes an attribute, checked against its type; type= creates a custom attribute.")
      .def_property_readonly("xform_op_names",
                             [](const PrimHandle& h) {
                               py::list names;
                               for (const XformOp& op : h.prim().xformOps()) names.append(op.attributeName());
                               return names;
                             })
      .def_property_readonly("xform_ops",
                             [](const PrimHandle& h) {
                               py::list ops;
                               for (const XformOp& op : h.prim().xformOps())
                                 ops.append(py::make_tuple(op.attributeName(), toPython(op.value)));
                               return ops;
                             })
      .def("get_location", [](const PrimHandle& h) {
             const Prim& p = h.prim();
             std::optional<size_t> i = findLocationOp(p);
             return vec3ToPython(i ? opLocation(p.xformOps()[*i]) : Vec3d::Zero());
           }, "The translation in the parent's frame (first translate or transform op).")
      .def("set_location",
           [](PrimHandle& h, py::handle v) { setOpLocation(locationOp(h), vec3FromPython(v, h.what("location"))); },
           py::arg("location"), "Writes the translation into the first translate (or transform) op, inserting one.")
      .def("get_world_location",
           [](const PrimHandle& h) { return vec3ToPython(worldLocation(h.ctx->liveStage(), h.prim())); })
      .def("set_world_location",
           [](PrimHandle& h, py::handle v) {
             Vec3d world = vec3FromPython(v, h.what("world location"));
             Matrix4d parent = parentWorld(h.ctx->liveStage(), h.prim());
             setOpLocation(locationOp(h), (parent.inverse() * world.homogeneous()).head<3>());
           },
           py::arg("location"), "Places the prim's origin at a world position (through its parent's transform).")
      .def("get_rotation", [](const PrimHandle& h) {
             const Prim& p = h.prim();
             std::optional<size_t> i = findRotationOp(p);
             return matrix3ToPython(i ? opRotation(p.xformOps()[*i]) : Matrix3d::Identity());
           }, "The rotation op's rotation (3x3, rows), identity without one.")
      .def("set_rotation",
           [](PrimHandle& h, py::handle r) { setOpRotation(rotationOp(h), matrix3FromPython(r, h.what("rotation"))); },
           py::arg("rotation"), "Writes a 3x3 rotation into the rotation op (orient inserted when there is none).")
      .def("get_world_rotation",
           [](const PrimHandle& h) { return matrix3ToPython(worldRotation(h.ctx->liveStage(), h.prim())); })
      .def("set_world_rotation",
           [](PrimHandle& h, py::handle r) {
             Matrix3d world = matrix3FromPython(r, h.what("world rotation"));
             const Prim& p = h.prim();
             Matrix3d parent =
                 p.parent()->isPseudoRoot() ? Matrix3d::Identity() : worldRotation(h.ctx->liveStage(), *p.parent());
             setOpRotation(rotationOp(h), parent.transpose() * world);
           },
           py::arg("rotation"), "Gives the prim a world rotation (its parent's rotation compensated).")
      .def("get_scale",
           [](const PrimHandle& h) {
             for (const XformOp& op : h.prim().xformOps()) {
               if (op.kind == XformOpKind::Scale && op.suffix.empty()) return vec3ToPython(op.value.get<Vec3d>());
               if (op.kind == XformOpKind::Transform) return vec3ToPython(decompose(op.value.get<Matrix4d>()).scale);
             }
             return vec3ToPython(Vec3d::Ones());
           },
           "The scale op's value (or a transform op's scale), (1, 1, 1) without one.")
      .def("set_scale",
           [](PrimHandle& h, py::handle s) {
             Vec3d scale = vec3FromPython(s, h.what("scale"));
             if (scale.minCoeff() <= 0) throw py::value_error(h.what("scale") + ": every component must be > 0");
             Prim& p = h.prim();
             if (!p.typeInfo().xformable) throw py::value_error(h.path + " has no transform");
             if (!h.ctx->created(p)) h.ctx->journal().beforeXformWrite(p);
             // The first scale op, else the scale part of the first transform
             // op, else a new scale op appended last (so it applies first).
             for (XformOp& op : p.xformOps()) {
               if (op.kind == XformOpKind::Scale && op.suffix.empty()) {
                 op.value = Value::makeDouble3(scale);
                 return;
               }
               if (op.kind == XformOpKind::Transform) {
                 Decomposed d = decompose(op.value.get<Matrix4d>());
                 op.value.get<Matrix4d>() = compose(d.translation, d.rotation, scale);
                 return;
               }
             }
             p.xformOps().push_back(XformOp{XformOpKind::Scale, "", Value::makeDouble3(scale)});
           },
           py::arg("scale"), "Writes the scale into xformOp:scale (or a transform op), appending a scale op when "
                             "there is neither.")
      .def("get_local_matrix", [](const PrimHandle& h) { return matrix4ToPython(h.prim().localMatrix()); },
           "4x4, column-vector convention (p_parent = M @ p).")
      .def("get_world_matrix",
           [](const PrimHandle& h) { return matrix4ToPython(h.ctx->liveStage().worldMatrix(h.prim())); },
           "4x4, column-vector convention (p_world = M @ p).")
      .def(
          "collider",
          [](const PrimHandle& h) -> py::object {
            // The geometry's collision shape in its own frame (mesh files loaded once per process, as
            // the built-in volumeStackRandomizer loads them); None for a prim with no geometry.
            const Prim& p = h.prim();
            if (!p.typeInfo().gprim) return py::none();
            if (!h.ctx->assets) throw py::value_error(h.path + ": no asset resolver to load its geometry");
            return py::cast(ColliderRef{ColliderCache::shared().get(meshKeyOf(p, h.ctx->liveStage().metadata().subdivisionLevel), *h.ctx->assets, h.path)});
          },
          "The prim's collider (its bounds: ((min x, y, z), (max x, y, z)) in its frame), or None.")
      .def_property_readonly("semantics",
                             [](const PrimHandle& h) {
                               py::dict d;
                               for (const auto& [type, labels] : h.prim().semantics()) d[py::str(type)] = labels;
                               return d;
                             })
      .def("get_semantic_labels",
           [](const PrimHandle& h, const std::string& taxonomy) {
             auto it = h.prim().semantics().find(taxonomy);
             return it == h.prim().semantics().end() ? std::vector<std::string>{} : it->second;
           },
           py::arg("taxonomy") = "class")
      .def("set_semantic_labels",
           [](PrimHandle& h, std::vector<std::string> labels, const std::string& taxonomy) {
             Prim& p = h.prim();
             if (!h.ctx->created(p)) h.ctx->journal().beforeSemanticsWrite(p);
             if (labels.empty()) p.semantics().erase(taxonomy);
             else p.semantics()[taxonomy] = std::move(labels);
           },
           py::arg("labels"), py::arg("taxonomy") = "class", "Replaces the labels of one taxonomy ([] removes it).")
      .def_property_readonly("material_path",
                             [](const PrimHandle& h) -> py::object {
                               const auto& m = h.prim().material();
                               return m ? py::object(py::str(m->path)) : py::object(py::none());
                             })
      .def_property_readonly("material_strength",
                             [](const PrimHandle& h) -> py::object {
                               const auto& m = h.prim().material();
                               return m ? py::object(py::str(m->strength)) : py::object(py::none());
                             })
      .def("bind_material",
           [](PrimHandle& h, const std::string& material, const std::string& strength) {
             Prim& p = h.prim();
             const Prim* m = h.ctx->liveStage().find(material);
             if (!m || m->type() != PrimType::Material)
               throw py::value_error(h.path + ".bind_material: " + material + " is not a Material prim");
             if (strength != "weakerThanDescendants" && strength != "strongerThanDescendants")
               throw py::value_error(h.path + ".bind_material: strength is weakerThanDescendants or "
                                              "strongerThanDescendants, found " + strength);
             if (!h.ctx->created(p)) h.ctx->journal().beforeMaterialWrite(p);
             p.material() = MaterialBinding{material, strength};
           },
           py::arg("material"), py::arg("strength") = "weakerThanDescendants")
      .def("unbind_material",
           [](PrimHandle& h) {
             Prim& p = h.prim();
             if (!h.ctx->created(p)) h.ctx->journal().beforeMaterialWrite(p);
             p.material().reset();
           })
      .def("__eq__", [](const PrimHandle& a, const PrimHandle& b) { return a.path == b.path; })
      .def("__hash__", [](const PrimHandle& h) { return py::hash(py::str(h.path)); })
      .def("__repr__", [](const PrimHandle& h) { return "<Prim " + h.path + ">"; });

  py::class_<StageHandle>(m, "Stage", "The stage the run plays.")
      .def("get_prim",
           [](StageHandle& s, const std::string& path) { return handleOrNone(s.ctx, s.ctx->liveStage().find(path)); },
           py::arg("path"), "The prim at path, or None.")
      .def("traverse", &traverse, py::arg("root") = py::none(),
           "Every prim below root (root included; the whole stage without one), pre-order.")
      .def("define_prim", &definePrim, py::arg("path"), py::arg("type_name") = "Xform",
           "Creates a prim under /Behaviors/<BEHAVIOR_NS>/; it is removed again on stop.")
      .def("remove_prim", &removePrim, py::arg("path"), "Removes a prim this behavior created.")
      .def("next_free_path",
           [](StageHandle& s, const std::string& path) { return nextFreePath(s.ctx->liveStage(), path); },
           py::arg("path"))
      .def(
          "resolve_asset",
          [](StageHandle& s, const std::string& path) -> py::object {
            s.ctx->liveStage();
            if (!s.ctx->assets) return py::none();
            std::optional<std::string> resolved = s.ctx->assets->resolve(path);
            if (!resolved) resolved = s.ctx->assets->resolveFolder(path);
            return resolved ? py::object(py::str(*resolved)) : py::object(py::none());
          },
          py::arg("path"),
          "The absolute path of a file or folder named as the scene names assets (absolute, or below the scene's "
          "folder, its asset_roots or an --asset-root), or None when none exists.")
      .def_property_readonly("meters_per_unit",
                             [](StageHandle& s) { return s.ctx->liveStage().metadata().metersPerUnit; })
      .def_property_readonly("up_axis", [](StageHandle& s) { return s.ctx->liveStage().metadata().upAxis; })
      .def_property_readonly("time_codes_per_second",
                             [](StageHandle& s) { return s.ctx->liveStage().metadata().timeCodesPerSecond; })
      .def(
          "set_metadata",
          [](StageHandle& s, std::optional<std::string> upAxis, std::optional<double> metersPerUnit) {
            if (!s.ctx->driver)
              throw py::value_error("set_metadata: a behavior cannot change the stage's up axis or units");
            StageMetadata& m = s.ctx->liveStage().metadata();
            if (upAxis) {
              if (*upAxis != "Y" && *upAxis != "Z")
                throw py::value_error("set_metadata: the up axis is Y or Z, found '" + *upAxis + "'");
              m.upAxis = *upAxis;
            }
            if (metersPerUnit) {
              if (!(*metersPerUnit > 0) || !std::isfinite(*metersPerUnit))
                throw py::value_error("set_metadata: metres per unit must be positive, found " +
                                      text::formatDouble(*metersPerUnit));
              m.metersPerUnit = *metersPerUnit;
            }
          },
          py::arg("up_axis") = py::none(), py::arg("meters_per_unit") = py::none(),
          "A driver program's (sdgbehave exec) change of the stage's up axis or metres per unit.");

  py::class_<ScriptContext, std::shared_ptr<ScriptContext>>(m, "Context", "A behavior's handle (self._ctx).")
      .def_property_readonly("prim", [](const ContextPtr& c) { c->liveStage(); return PrimHandle{c, c->primPath}; })
      .def_property_readonly("prim_path", [](const ContextPtr& c) { return c->primPath; })
      .def_property_readonly("stage", [](const ContextPtr& c) { c->liveStage(); return StageHandle{c}; })
      .def_property_readonly("rng", [](const ContextPtr& c) -> Rng& { return c->randomStream(); },
                             py::return_value_policy::reference_internal)
      .def("get_exposed_variable",
           [](const ContextPtr& c, const std::string& name) -> py::object {
             const Prim* p = c->liveStage().find(c->primPath);
             const Value* v = p ? p->value(exposedAttributeName(c->ns(), name)) : nullptr;
             return v ? toPython(*v) : py::object(py::none());
           })
      .def("publish",
           [](const ContextPtr& c, const std::string& event, const py::dict& payload) {
             c->liveStage();
             c->events->publish(event, payloadFromPython(payload, "publish " + event));
           })
      .def("subscribe",
           [](const ContextPtr& c, const std::string& event, py::function callback) {
             c->liveStage();
             // Watched like a hook: a Python error, a timeout or an exit in the
             // callback stops the run, naming the callback.
             EventBus::Subscription id = c->events->subscribe(
                 event, [callback, prim = c->primPath, ns = c->ns(), script = c->script,
                         hook = "the callback for event '" + event + "'"](const Payload& payload) {
                   activity::HookScope scope(prim, ns, hook, activity::HookScope::Kind::Callback);
                   callScript(
                       script, [&] { return prim + ": " + ns + ": " + hook; },
                       [&] { callback(payloadToPython(payload)); });
                 });
             c->subscriptions.push_back(id);
             return id;
           })
      .def("unsubscribe", [](const ContextPtr& c, EventBus::Subscription id) {
        c->liveStage();
        c->events->unsubscribe(id);
        std::erase(c->subscriptions, id);
      });
}

}  // namespace sdg::scripting
