#pragma once
// Subdivision surfaces (USD's catmullClark, loop and bilinear schemes, with
// creases, corners, holes and the boundary and face-varying rules) refined
// with OpenSubdiv's Far API on the CPU: uniform refinement to the mesh's
// level, then every point moved onto the limit surface. The only file that
// includes OpenSubdiv is subdivision.cpp.
#include <string>

#include "assets/inline_mesh.h"

namespace sdg {

// What is wrong with a refined mesh's tags against its topology ("" when
// nothing): crease lengths that do not add up to the crease indices, a
// number of sharpnesses that is neither per crease nor per crease edge,
// indices outside the points, loop on a face that is no triangle,
// a refinement past kMaxMeshTriangles. The arrays themselves are checked
// first (inlineMeshProblem).
std::string subdivisionProblem(const InlineMesh& mesh);

// The polygons of `mesh` refined mesh.subdivision.level times: points on
// the limit surface, faces of the last level less the holes, primvars:st
// refined as face-varying data (corners of a point that share a value share
// it in the refinement, so seams stay seams) and written per face-vertex,
// the per-corner colour and opacity the same way;
// no normals (the mesh's authored normals do not apply to the refined
// surface, as in USD): the triangulation computes them smooth. RunError
// naming `primPath` when OpenSubdiv refuses the topology.
InlineMesh refineSubdivisionSurface(const InlineMesh& mesh, const std::string& primPath);

}  // namespace sdg
