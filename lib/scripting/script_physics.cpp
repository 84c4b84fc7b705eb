#include "scripting/script_physics.h"

#include <pybind11/stl.h>

#include "physics/physics_world.h"
#include "scripting/value_convert.h"

namespace py = pybind11;

namespace sdg::scripting {
namespace {

Eigen::Quaterniond quatFromPython(py::handle object, const std::string& what) {
  py::sequence s = py::reinterpret_borrow<py::sequence>(object);
  if (py::len(s) != 4) throw py::value_error(what + ": expected a quaternion (w, x, y, z)");
  Eigen::Quaterniond q(s[0].cast<double>(), s[1].cast<double>(), s[2].cast<double>(), s[3].cast<double>());
  if (!(q.norm() > 0)) throw py::value_error(what + ": a zero quaternion");
  return q.normalized();
}

PhysicsWorld::BodyId checkedBody(const PhysicsWorld& w, size_t id) {
  if (id >= w.bodyCount()) throw py::index_error("no body " + std::to_string(id) + " in this physics world");
  return id;
}

}  // namespace

void bindPhysics(py::module_& m) {
  py::class_<ColliderRef>(m, "Collider", "A prim's collision shape (box, sphere, capsule or convex hull).")
      .def_property_readonly("bounds", [](const ColliderRef& c) {
        return py::make_tuple(vec3ToPython(c.collider->bounds.min()), vec3ToPython(c.collider->bounds.max()));
      });

  py::class_<PhysicsWorld>(m, "PhysicsWorld", "sdgbehave's ODE world (the one volumeStackRandomizer stacks with).")
      .def(py::init([](double dt, py::handle gravity, double linearDamping, double angularDamping) {
             PhysicsWorld::Config config;
             if (!(dt > 0)) throw py::value_error("PhysicsWorld: the step must be positive, found " + std::to_string(dt));
             config.dt = dt;
             config.gravity = vec3FromPython(gravity, "PhysicsWorld gravity");
             config.linearDamping = linearDamping;
             config.angularDamping = angularDamping;
             return std::make_unique<PhysicsWorld>(config);
           }),
           py::arg("dt"), py::arg("gravity"), py::arg("linear_damping"), py::arg("angular_damping"))
      .def(
          "add_body",
          [](PhysicsWorld& w, const ColliderRef& c, py::handle position, py::handle orientation, std::string name) {
            BodyPose pose{vec3FromPython(position, name + " position"), quatFromPython(orientation, name)};
            return w.addBody(c.collider, pose, std::move(name));
          },
          py::arg("collider"), py::arg("position"), py::arg("orientation"), py::arg("name"))
      .def(
          "add_static_box",
          [](PhysicsWorld& w, py::handle halfExtents, py::handle center, py::handle rotation) {
            w.addStaticBox(vec3FromPython(halfExtents, "static box half extents"),
                           vec3FromPython(center, "static box centre"), matrix3FromPython(rotation, "static box rotation"));
          },
          py::arg("half_extents"), py::arg("center"), py::arg("rotation"))
      .def("set_friction", &PhysicsWorld::setFriction, py::arg("mu"))
      .def(
          "add_force_at_point",
          [](PhysicsWorld& w, size_t id, py::handle force, py::handle point) {
            w.addForceAtPoint(checkedBody(w, id), vec3FromPython(force, "force"), vec3FromPython(point, "point"));
          },
          py::arg("body"), py::arg("force"), py::arg("point"))
      .def("step", &PhysicsWorld::step)
      .def("remove_body", [](PhysicsWorld& w, size_t id) { w.removeBody(checkedBody(w, id)); }, py::arg("body"))
      .def(
          "pose",
          [](const PhysicsWorld& w, size_t id) {
            BodyPose p = w.pose(checkedBody(w, id));
            const Eigen::Quaterniond& q = p.orientation;
            return py::make_tuple(vec3ToPython(p.position), py::make_tuple(q.w(), q.x(), q.y(), q.z()));
          },
          py::arg("body"), "((x, y, z), (w, x, y, z)) of the body's prim origin.")
      .def_property_readonly("step_count", &PhysicsWorld::stepCount);
}

}  // namespace sdg::scripting
