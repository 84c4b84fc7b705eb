#pragma once
// USD's procedural shapes as triangle meshes, with USD's attributes and
// defaults: Cube (size 2), Sphere (radius 1), Cylinder and Cone (radius 1,
// height 2), Capsule (radius 0.5, height 1 without the caps), Plane (width
// and length 2), each centred at the origin and aligned with `axis`.
#include "assets/mesh_data.h"

namespace sdg {

MeshData makeCube(double size);
MeshData makeSphere(double radius);
MeshData makeCylinder(double radius, double height, char axis);
MeshData makeCone(double radius, double height, char axis);
MeshData makeCapsule(double radius, double height, char axis);
// A Plane's width runs along the first and its length along the second of
// the two axes other than `axis`, in X, Y, Z order.
MeshData makePlane(double width, double length, char axis);

}  // namespace sdg
