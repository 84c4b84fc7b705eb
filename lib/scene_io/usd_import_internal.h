#pragma once
// Pieces of the USD mapping shared by the driver (usd_import.cpp): value
// conversion, transforms and units, geometry. Internal to scene_io.
#include <optional>
#include <string>

#include "core/diagnostics.h"
#include "stage/prim.h"
#include "usd/compose.h"

namespace sdg::usd_map {

// A composed value as a stage value of `type` (numbers of any precision
// converted; color3f[] / float[] of one item accepted for a scalar, as USD
// writes displayColor). nullopt when the shapes do not match.
std::optional<Value> toStageValue(const usd::Value& value, ValueType type);

// The xformOpOrder of `prim` as stage ops: every op kind, `!invert!`
// baked into a transform op, `!resetXformStack!` baked against
// `parentWorld` (the parent's world matrix at import). Problems go to diag.
std::vector<XformOp> xformOpsOf(const usd::ComposedPrim& prim, const Matrix4d& parentWorld, Diagnostics& diag);

// The transform that carries geometry in `from` units into `to` units
// (scale by the metres-per-unit ratio, rotate a Y-up layer into Z-up and
// back), as ops; empty when the units agree.
std::vector<XformOp> unitsOps(const usd::LayerUnits& from, const usd::LayerUnits& to);
double unitsScale(const usd::LayerUnits& from, const usd::LayerUnits& to);

// A composed Mesh's geometry onto a stage Mesh prim: points, counts and
// indices, normals, primvars:st and non-constant displayColor /
// displayOpacity of every interpolation (indexed ones expanded) written per
// face-vertex, subdivisionScheme, orientation.
// `faces` (when given) keeps only those faces (a GeomSubset's).
// primvars:displayColor and primvars:displayOpacity (usd_display_primvars.cpp).
// Whether the name is one of them.
bool isDisplayPrimvar(const std::string& name);
// Whether one of them is not constant: an authored interpolation other than
// "constant", or none and more than one element.
bool isVaryingDisplayPrimvar(const usd::ComposedPrim& prim, const usd::ComposedProperty& p);
// The interpolation of a varying one: authored, else the one its element
// count fits (vertex, faceVarying, uniform); nullopt after an error.
std::optional<std::string> displayPrimvarInterpolation(const usd::ComposedPrim& mesh, const usd::ComposedProperty& p,
                                                       size_t faces, size_t points, size_t corners, Diagnostics& diag);
// A gprim's constant one onto the stage attribute of the same name (the
// first element of a non-constant one on a gprim that is not a Mesh, with
// a warning); true when `p` is one of them (handled, or reported).
bool importDisplayPrimvar(const usd::ComposedPrim& prim, const usd::ComposedProperty& p, PrimType type, Prim& stagePrim,
                          Diagnostics& diag);

void importMeshGeometry(const usd::ComposedPrim& mesh, Prim& stagePrim, const std::vector<int32_t>* faces,
                        Diagnostics& diag);

// Its subdivision arrays (usd_subdivision.cpp): creases, corners, and
// holeIndices renumbered to the kept `faces` (authored face indices).
void importSubdivisionTags(const usd::ComposedPrim& mesh, Prim& stagePrim, const std::vector<size_t>& faces,
                           Diagnostics& diag);

}  // namespace sdg::usd_map
