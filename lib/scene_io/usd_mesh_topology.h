#pragma once
// A composed USD Mesh checked before importMeshGeometry indexes with it: a
// file is untrusted input, and a negative face count or an index past the
// points would otherwise read (or loop) outside the arrays. Each problem is
// reported once, at the file:line:col of the attribute, naming the prim
// path and attribute and saying what was expected and what was found.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "usd/compose.h"

namespace sdg::usd_map {

// Checks, on the composed values (doubles, so a value too large for an int
// is caught before anything converts it):
//   faceVertexCounts   whole numbers, each at least 3 (a face needs three corners)
//   faceVertexIndices  whole numbers, as many as the counts add up to, each
//                      one of the points (0 <= i < number of points)
//   points             finite (as float: 1e39 is infinite once read)
//   primvars           normals, primvars:normals, primvars:st and the other
//                      texCoord2 primvars, primvars:displayColor and
//                      primvars:displayOpacity, when authored: a known
//                      interpolation and at least the items it needs
//                      (constant 1, uniform one per face, vertex/varying one
//                      per point, faceVarying one per face-vertex); an
//                      indexed one's `:indices` as many as that, each one
//                      of its values.
// `fallback` interpolations are the importer's: vertex for normals and
// texture coordinates, constant for displayColor/displayOpacity. A mesh
// without points is left to the importer, which reports it. True when the
// mesh can be imported as it is.
bool checkMeshTopology(const usd::ComposedPrim& mesh, Diagnostics& diag);

// A primvar's authored `interpolation` metadata; `fallback` when it has none.
std::string primvarInterpolation(const usd::ComposedProperty& p, const std::string& fallback = "");

// The faces a GeomSubset's `indices` name, each a whole number inside the
// mesh's `faceCount` faces; nullopt after reporting one that is not (at the
// subset's `indices`, naming the mesh).
std::optional<std::vector<int32_t>> subsetFaces(const usd::ComposedPrim& subset, const std::string& meshPath,
                                                size_t faceCount, Diagnostics& diag);

}  // namespace sdg::usd_map
