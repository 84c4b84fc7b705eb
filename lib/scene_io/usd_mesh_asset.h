#pragma once
// A USD file as a mesh asset (`asset: chair.usd` on a Mesh prim): its Mesh
// prims imported as a USD stage is (usd_import.h) into a stage of their
// own, triangulated, with their world transforms and the file's units and
// up axis applied (a Y-up centimetre file comes out Z-up in metres), one
// part per Mesh prim carrying its bound material's diffuse colour or
// texture, roughness and metallic (else its displayColor).
#include <string>

#include "assets/mesh_data.h"

namespace sdg {

// `submesh` "" = every Mesh prim; else a prim path in the file: the Mesh
// prims at or under it. RunError naming the file for composition errors,
// a file without meshes, or a submesh that names none.
MeshData loadUsdMeshAsset(const std::string& path, const std::string& submesh);

// Installs loadUsdMeshAsset as the assets library's USD mesh reader
// (assets/mesh_loader.h). Each program that draws scenes calls it once when
// it starts (the CLI's main, the unit tests' main, the developer tools):
// the assets library lies below scene_io and cannot reach the reader itself.
void registerUsdMeshAssets();

}  // namespace sdg
