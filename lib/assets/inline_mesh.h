#pragma once
// Geometry written on a Mesh prim itself (a USD mesh: points,
// faceVertexCounts, faceVertexIndices, normals, primvars:st) rather than in
// a mesh file. The arrays are shared Values, so keeping them in a MeshKey
// is cheap; triangulation happens once per cache (renderer, colliders),
// keyed by the arrays' content hashes. A subdivision surface is refined
// first (assets/subdivision.h), to the level the stage is drawn at.
#include <memory>
#include <optional>
#include <string>

#include "assets/mesh_data.h"
#include "stage/prim.h"

namespace sdg {

// A subdivision surface's scheme and tags, USD's names and tokens (UsdGeomMesh).
struct SubdivisionSurface {
  std::string scheme;  // catmullClark, loop or bilinear
  int level = 0;       // uniform refinements (render.subdivision_level); 0 draws the authored polygons
  std::string interpolateBoundary = "edgeAndCorner", faceVaryingLinearInterpolation = "cornersPlus1",
              triangleSubdivisionRule = "catmullClark";
  Value creaseIndices = Value::makeIntArray({}), creaseLengths = Value::makeIntArray({}),
        creaseSharpnesses = Value::makeFloatArray(ValueType::FloatArray, {}), cornerIndices = Value::makeIntArray({}),
        cornerSharpnesses = Value::makeFloatArray(ValueType::FloatArray, {});
};

struct InlineMesh {
  Value points, faceVertexCounts, faceVertexIndices;
  std::optional<Value> normals, st;
  // primvars:displayColor:faceVarying and primvars:displayOpacity:faceVarying:
  // one item per face-vertex (MeshData::colors when either is present).
  std::optional<Value> displayColor, displayOpacity;
  bool flat = false;         // subdivisionScheme "none": faceted normals where none are given
  bool leftHanded = false;   // orientation "leftHanded": faces wind clockwise
  Value holeIndices = Value::makeIntArray({});  // faces not drawn, refined or not (as in USD)
  SubdivisionSurface subdivision;  // refined when subdivision.level > 0
  bool refined() const { return subdivision.level > 0; }
  std::string id() const;    // "inline:" + the content hashes
};

// The inline geometry of a Mesh prim; null when it has no authored points.
// `subdivisionLevel` (the stage's, StageMetadata) applies to a Mesh whose
// subdivisionScheme is not "none".
std::shared_ptr<const InlineMesh> inlineMeshOf(const Prim& prim, int subdivisionLevel);

// What is wrong with the arrays ("" when nothing): a face of fewer than 3
// corners, counts that do not add up to the indices, indices outside the
// points, a point that is not finite, primvars of a length that is neither
// per point nor per face-vertex, per-corner colours or opacities that are
// not one per face-vertex, subdivision tags that do not fit the mesh.
// `attribute` (when given) receives the name of the
// attribute at fault, to locate the message.
std::string inlineMeshProblem(const InlineMesh& mesh, std::string* attribute = nullptr);

// Fan-triangulates the faces, refined first when mesh.refined() (RunError
// naming `primPath` on a problem).
MeshData triangulateInlineMesh(const InlineMesh& mesh, const std::string& primPath);

}  // namespace sdg
