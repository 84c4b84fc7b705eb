#pragma once
// Where a geometry prim's triangles come from: a procedural shape with its
// USD attributes, or a mesh file. The renderer and the physics colliders
// both go through here, so they always agree on a prim's geometry.
#include <string>

#include "assets/asset_resolver.h"
#include "assets/inline_mesh.h"
#include "assets/mesh_data.h"
#include "stage/prim.h"

namespace sdg {

// What geometry to draw: a procedural shape or an asset file.
struct MeshKey {
  PrimType shape = PrimType::Cube;  // Mesh for files
  std::string asset;                // resolved later by the renderer's cache
  std::string submesh;
  double a = 0, b = 0, c = 0;       // size / radius, height / width, length
  char axis = 'Z';
  std::shared_ptr<const InlineMesh> inlineMesh;  // a Mesh with inline geometry (asset empty)
  std::string id() const;           // a stable cache key
};

// The key of a geometry prim (Mesh, Cube, Sphere, Cylinder, Cone, Capsule,
// Plane); a subdivision surface is refined `subdivisionLevel` times (the
// stage's: StageMetadata::subdivisionLevel).
MeshKey meshKeyOf(const Prim& prim, int subdivisionLevel);

// Generates or loads the mesh of a key; a missing or unreadable file is a
// RunError naming `primPath` and every place searched.
MeshData meshDataFor(const MeshKey& key, const AssetResolver& assets, const std::string& primPath);

}  // namespace sdg
