#pragma once
// Mesh files through assimp: OBJ (+MTL), glTF/GLB, FBX, PLY, STL, DAE.
// Triangulated, normals generated where missing, node transforms baked in,
// the file's unit scale applied (FBX's UnitScaleFactor; glTF is metres),
// one part per material with its base colour, texture, roughness, metallic.
#include <string>

#include "assets/mesh_data.h"

namespace sdg {

// Documented limit: meshes above this many triangles are refused.
inline constexpr size_t kMaxMeshTriangles = 50'000'000;

// USD files (.usd, .usda, .usdc, .usdz) as mesh assets: their Mesh prims
// (or those at or under the prim path `submesh`) with world transforms and
// units applied, one part per prim with its bound material. Reading them
// needs composition and the USD mapping (scene_io/usd_mesh_asset.cpp), which
// lie above this library, so scene_io installs the reader when it loads a
// scene; until then a USD mesh is a RunError saying so.
using UsdMeshReader = MeshData (*)(const std::string& path, const std::string& submesh);
void setUsdMeshReader(UsdMeshReader reader);

// Loads `path` (or only the meshes named `submesh`); throws RunError naming
// the file for unreadable, corrupt or unsupported files, NaN vertices, no
// triangles, or more than kMaxMeshTriangles.
MeshData loadMeshFile(const std::string& path, const std::string& submesh = "");

}  // namespace sdg
