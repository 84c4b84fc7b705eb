#include "assets/mesh_loader.h"

#include <cmath>
#include <filesystem>

#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "core/diagnostics.h"

namespace sdg {
namespace {

MeshPart partFromMaterial(const aiMaterial* material, const std::filesystem::path& folder) {
  MeshPart part;
  if (!material) return part;
  part.hasMaterial = true;
  aiColor4D color;
  if (material->Get(AI_MATKEY_BASE_COLOR, color) == AI_SUCCESS ||
      material->Get(AI_MATKEY_COLOR_DIFFUSE, color) == AI_SUCCESS)
    part.baseColor = Vec3f(color.r, color.g, color.b);
  float value = 0;
  if (material->Get(AI_MATKEY_ROUGHNESS_FACTOR, value) == AI_SUCCESS) part.roughness = value;
  if (material->Get(AI_MATKEY_METALLIC_FACTOR, value) == AI_SUCCESS) part.metallic = value;
  aiString texture;
  if (material->GetTexture(aiTextureType_BASE_COLOR, 0, &texture) == AI_SUCCESS ||
      material->GetTexture(aiTextureType_DIFFUSE, 0, &texture) == AI_SUCCESS) {
    std::string name = texture.C_Str();
    // Embedded textures ("*0") are not supported; the base colour stands in.
    if (!name.empty() && name[0] != '*') part.texture = (folder / name).lexically_normal().string();
  }
  return part;
}

}  // namespace

MeshData loadMeshFile(const std::string& path, const std::string& submesh) {
  Assimp::Importer importer;
  // Points and lines carry no surface; drop them during import.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const unsigned flags = aiProcess_Triangulate | aiProcess_GenSmoothNormals | aiProcess_JoinIdenticalVertices |
                         aiProcess_SortByPType | aiProcess_PreTransformVertices | aiProcess_ValidateDataStructure;
  const aiScene* scene = importer.ReadFile(path, flags);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    throw RunError(path + ": cannot read the mesh: " + importer.GetErrorString());

  double unitScale = 1.0;
  if (scene->mMetaData) {
    double factor = 0;
    float factorF = 0;
    // FBX stores centimetres per unit; sdgbehave works in the file's metres.
    if (scene->mMetaData->Get("UnitScaleFactor", factor) && factor > 0) unitScale = factor / 100.0;
    else if (scene->mMetaData->Get("UnitScaleFactor", factorF) && factorF > 0) unitScale = factorF / 100.0;
  }

  std::filesystem::path folder = std::filesystem::path(path).parent_path();
  MeshData mesh;
  size_t triangles = 0;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* in = scene->mMeshes[m];
    if (!submesh.empty() && submesh != in->mName.C_Str()) continue;
    if (!(in->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    triangles += in->mNumFaces;
    if (triangles > kMaxMeshTriangles)
      throw RunError(path + ": more than " + std::to_string(kMaxMeshTriangles) +
                     " triangles; split the mesh or decimate it");
    uint32_t base = static_cast<uint32_t>(mesh.positions.size());
    for (unsigned v = 0; v < in->mNumVertices; ++v) {
      const aiVector3D& p = in->mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        throw RunError(path + ": vertex " + std::to_string(v) + " of mesh '" + in->mName.C_Str() +
                       "' is not a finite number");
      mesh.positions.emplace_back(float(p.x * unitScale), float(p.y * unitScale), float(p.z * unitScale));
      const aiVector3D n = in->mNormals ? in->mNormals[v] : aiVector3D(0, 0, 1);
      Vec3f normal(n.x, n.y, n.z);
      mesh.normals.push_back(std::isfinite(normal.squaredNorm()) && normal.squaredNorm() > 0 ? normal.normalized()
                                                                                             : Vec3f(0, 0, 1));
      if (in->mTextureCoords[0]) mesh.uvs.emplace_back(in->mTextureCoords[0][v].x, in->mTextureCoords[0][v].y);
      else mesh.uvs.emplace_back(0.0f, 0.0f);
    }
    MeshPart part = partFromMaterial(in->mMaterialIndex < scene->mNumMaterials ? scene->mMaterials[in->mMaterialIndex]
                                                                                : nullptr,
                                     folder);
    part.firstIndex = static_cast<uint32_t>(mesh.indices.size());
    for (unsigned f = 0; f < in->mNumFaces; ++f) {
      const aiFace& face = in->mFaces[f];
      if (face.mNumIndices != 3) continue;
      for (unsigned k = 0; k < 3; ++k) mesh.indices.push_back(base + face.mIndices[k]);
    }
    part.indexCount = static_cast<uint32_t>(mesh.indices.size()) - part.firstIndex;
    if (part.indexCount) mesh.parts.push_back(part);
  }
  if (mesh.indices.empty())
    throw RunError(path + (submesh.empty() ? std::string(": the file has no triangles")
                                           : ": no mesh named '" + submesh + "' with triangles"));
  mesh.updateBounds();
  return mesh;
}

}  // namespace sdg
