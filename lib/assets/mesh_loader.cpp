#include "assets/mesh_loader.h"

#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <assimp/GltfMaterial.h>
#include <assimp/Importer.hpp>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include "core/diagnostics.h"

namespace sdg {
namespace {

// A content key for embedded images: the same picture in two files (or
// twice in one) is decoded and uploaded once.
std::string contentKey(const uint8_t* bytes, size_t size, uint32_t width, uint32_t height) {
  uint64_t hash = 1469598103934665603ull;  // FNV-1a, 64 bits
  auto mix = [&](uint8_t b) { hash = (hash ^ b) * 1099511628211ull; };
  for (size_t i = 0; i < size; ++i) mix(bytes[i]);
  for (int shift = 0; shift < 32; shift += 8) {
    mix(uint8_t(width >> shift));
    mix(uint8_t(height >> shift));
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return std::string("embedded:") + text;
}

// Turns the texture a material names into a texture key: an embedded image
// (assimp's "*N", or a file name that matches an embedded texture, as FBX
// files store them) is copied into mesh.embeddedImages; anything else is a
// file beside the mesh file.
class TextureNamer {
 public:
  TextureNamer(const aiScene& scene, const std::string& path, MeshData& mesh)
      : scene_(scene), path_(path), folder_(std::filesystem::path(path).parent_path()), mesh_(mesh) {}

  std::string keyOf(const aiString& name) {
    const std::string text = name.C_Str();
    if (text.empty()) return {};
    const aiTexture* embedded = scene_.GetEmbeddedTexture(name.C_Str());
    if (!embedded) {
      if (text[0] == '*') throw RunError(path_ + ": a material names embedded texture " + text + ", which the file lacks");
      return (folder_ / text).lexically_normal().string();
    }
    EmbeddedImage image;
    image.name = std::filesystem::path(path_).filename().string() + "[" + text + "]";
    const auto* data = reinterpret_cast<const uint8_t*>(embedded->pcData);
    if (embedded->mHeight == 0) {  // compressed: mWidth bytes in the file's format
      image.bytes = std::make_shared<std::vector<uint8_t>>(data, data + embedded->mWidth);
    } else {  // raw texels (aiTexel is b, g, r, a)
      image.rawWidth = embedded->mWidth;
      image.rawHeight = embedded->mHeight;
      image.bytes = std::make_shared<std::vector<uint8_t>>(data, data + size_t(embedded->mWidth) * embedded->mHeight * 4);
    }
    image.key = contentKey(image.bytes->data(), image.bytes->size(), image.rawWidth, image.rawHeight);
    for (const EmbeddedImage& known : mesh_.embeddedImages)
      if (known.key == image.key) return known.key;
    mesh_.embeddedImages.push_back(image);
    return image.key;
  }

  // The first texture of `type` the material names, as a key ("" for none).
  std::string texture(const aiMaterial& material, aiTextureType type) {
    aiString name;
    if (material.GetTextureCount(type) == 0 || material.GetTexture(type, 0, &name) != AI_SUCCESS) return {};
    return keyOf(name);
  }

 private:
  const aiScene& scene_;
  std::string path_;
  std::filesystem::path folder_;
  MeshData& mesh_;
};

// The part's material as glTF's metallic-roughness model describes it
// (other formats fill what they have: diffuse colour and texture, normals).
MeshPart partFromMaterial(const aiMaterial* material, TextureNamer& textures) {
  MeshPart part;
  if (!material) return part;
  part.hasMaterial = true;
  aiColor4D color;
  if (material->Get(AI_MATKEY_BASE_COLOR, color) == AI_SUCCESS ||
      material->Get(AI_MATKEY_COLOR_DIFFUSE, color) == AI_SUCCESS) {
    part.baseColor = Vec3f(color.r, color.g, color.b);
    part.opacityConstant = color.a;
  }
  float value = 0;
  if (material->Get(AI_MATKEY_ROUGHNESS_FACTOR, value) == AI_SUCCESS) part.roughness = value;
  if (material->Get(AI_MATKEY_METALLIC_FACTOR, value) == AI_SUCCESS) part.metallic = value;
  part.maps.baseColor = textures.texture(*material, aiTextureType_BASE_COLOR);
  if (part.maps.baseColor.empty()) part.maps.baseColor = textures.texture(*material, aiTextureType_DIFFUSE);
  // glTF's metallicRoughness texture packs roughness in green and metallic
  // in blue, as an ORM texture does; assimp hands it over as "unknown".
  part.maps.orm = textures.texture(*material, aiTextureType_UNKNOWN);
  if (part.maps.orm.empty()) part.maps.orm = textures.texture(*material, aiTextureType_METALNESS);
  part.maps.normal = textures.texture(*material, aiTextureType_NORMALS);
  if (!part.maps.normal.empty() &&
      material->Get(AI_MATKEY_GLTF_TEXTURE_SCALE(aiTextureType_NORMALS, 0), value) == AI_SUCCESS)
    part.normalScale = value;
  aiString alphaMode;
  if (material->Get(AI_MATKEY_GLTF_ALPHAMODE, alphaMode) == AI_SUCCESS) {
    const std::string mode = alphaMode.C_Str();
    // BLEND (partial transparency) is drawn as a cut-out at one half.
    if (mode == "MASK" || mode == "BLEND") {
      part.opacity = part.maps.baseColor.empty() ? OpacitySource::Constant : OpacitySource::BaseColorAlpha;
      part.opacityCutoff = 0.5f;
      if (mode == "MASK" && material->Get(AI_MATKEY_GLTF_ALPHACUTOFF, value) == AI_SUCCESS) part.opacityCutoff = value;
    }
  }
  return part;
}

}  // namespace

namespace {
std::atomic<UsdMeshReader> gUsdMeshReader{nullptr};

bool isUsdMeshFile(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".usd" || ext == ".usda" || ext == ".usdc" || ext == ".usdz";
}
}  // namespace

void setUsdMeshReader(UsdMeshReader reader) { gUsdMeshReader.store(reader); }

MeshData loadMeshFile(const std::string& path, const std::string& submesh) {
  if (isUsdMeshFile(path)) {
    const UsdMeshReader reader = gUsdMeshReader.load();
    if (!reader) throw RunError(path + ": no USD mesh reader is installed; a program that draws scenes calls registerUsdMeshAssets() "
                                  "(scene_io/usd_mesh_asset.h) when it starts");
    MeshData mesh = reader(path, submesh);
    if (mesh.triangleCount() > kMaxMeshTriangles)
      throw RunError(path + ": " + std::to_string(mesh.triangleCount()) + " triangles; meshes are limited to " +
                     std::to_string(kMaxMeshTriangles));
    return mesh;
  }
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

  MeshData mesh;
  TextureNamer textures(*scene, path, mesh);
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
                                     textures);
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
