// The native module's Prim: attributes checked against their types, xform
// ops written exactly as the built-in behaviors write them
// (stage/xform_edit.h), semantics and material bindings; every write goes
// through the behavior's journal first, so sdgbehave can undo it.
#include <pybind11/embed.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <optional>

#include "assets/asset_resolver.h"
#include "behavior/behavior_prims.h"
#include "core/text.h"
#include "scripting/script_bindings.h"
#include "scripting/script_physics.h"
#include "scripting/value_convert.h"
#include "stage/look_at.h"
#include "stage/path.h"
#include "stage/prim_types.h"
#include "stage/xform_edit.h"

namespace py = pybind11;

namespace sdg::scripting {
namespace {

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

void bindPrim(py::module_& m) {
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
}

}  // namespace sdg::scripting
