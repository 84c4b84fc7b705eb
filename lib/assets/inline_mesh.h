#pragma once
// Geometry written on a Mesh prim itself (a USD mesh: points,
// faceVertexCounts, faceVertexIndices, normals, primvars:st) rather than in
// a mesh file. The arrays are shared Values, so keeping them in a MeshKey
// is cheap; triangulation happens once per cache (renderer, colliders),
// keyed by the arrays' content hashes.
#include <memory>
#include <optional>
#include <string>

#include "assets/mesh_data.h"
#include "stage/prim.h"

namespace sdg {

struct InlineMesh {
  Value points, faceVertexCounts, faceVertexIndices;
  std::optional<Value> normals, st;
  // primvars:displayColor:faceVarying and primvars:displayOpacity:faceVarying:
  // one item per face-vertex (MeshData::colors when either is present).
  std::optional<Value> displayColor, displayOpacity;
  bool flat = false;         // subdivisionScheme "none": faceted normals where none are given
  bool leftHanded = false;   // orientation "leftHanded": faces wind clockwise
  std::string id() const;    // "inline:" + the content hashes
};

// The inline geometry of a Mesh prim; null when it has no authored points.
std::shared_ptr<const InlineMesh> inlineMeshOf(const Prim& prim);

// What is wrong with the arrays ("" when nothing): a face of fewer than 3
// corners, counts that do not add up to the indices, indices outside the
// points, a point that is not finite, primvars of a length that is neither
// per point nor per face-vertex, per-corner colours or opacities that are
// not one per face-vertex. `attribute` (when given) receives the name of the
// attribute at fault, to locate the message.
std::string inlineMeshProblem(const InlineMesh& mesh, std::string* attribute = nullptr);

// Fan-triangulates the faces (RunError naming `primPath` on a problem).
MeshData triangulateInlineMesh(const InlineMesh& mesh, const std::string& primPath);

}  // namespace sdg
