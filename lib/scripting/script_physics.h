#pragma once
// The `_sdgbehave` binding of the project's ODE world (physics/physics_world.h)
// for the Isaac layer's omni.physx mapping: bodies from colliders of prims,
// static boxes, forces, steps and poses. Vectors are tuples, rotations 3x3
// in the column-vector convention (world = R * local), quaternions (w, x, y, z).
#include <memory>

#include <pybind11/pybind11.h>

#include "physics/collider.h"

namespace sdg::scripting {

// A prim's collider, as Prim.collider() hands it to Python.
struct ColliderRef {
  std::shared_ptr<const Collider> collider;
};

void bindPhysics(pybind11::module_& m);

}  // namespace sdg::scripting
