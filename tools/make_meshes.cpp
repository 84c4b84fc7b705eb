// Generates the small mesh files under scenes/props/ and tests/data/meshes/
// (made by this project; see third_party_notes/project-assets.md): a crate
// with two materials, written in every format sdgbehave reads, through
// assimp's exporters. Deterministic: running it again rewrites the same files.
//
//   build/release/tools/sdg_make_meshes <output folder>
#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Vertex {
  float p[3], n[3], uv[2];
};

// One axis-aligned box of half-extents h centred at c: 24 vertices, 12 triangles.
void addBox(std::vector<Vertex>& v, std::vector<unsigned>& idx, const float c[3], const float h[3]) {
  const float normals[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const auto& n : normals) {
    int a = n[0] != 0 ? 0 : n[1] != 0 ? 1 : 2;  // normal axis
    int u = (a + 1) % 3, w = (a + 2) % 3;
    float s = n[a];
    unsigned base = unsigned(v.size());
    const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& k : corners) {
      Vertex x{};
      x.p[a] = c[a] + s * h[a];
      x.p[u] = c[u] + k[0] * h[u];
      x.p[w] = c[w] + k[1] * h[w];
      for (int i = 0; i < 3; ++i) x.n[i] = n[i];
      x.uv[0] = (k[0] + 1) / 2;
      x.uv[1] = (k[1] + 1) / 2;
      v.push_back(x);
    }
    // Counter-clockwise seen from outside: (u x w) = a-axis, flip for negative faces.
    if (s > 0) idx.insert(idx.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    else idx.insert(idx.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
  }
}

aiMesh* makeMesh(const char* name, const std::vector<Vertex>& v, const std::vector<unsigned>& idx, unsigned material) {
  auto* mesh = new aiMesh();
  mesh->mName = name;
  mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  mesh->mMaterialIndex = material;
  mesh->mNumVertices = unsigned(v.size());
  mesh->mVertices = new aiVector3D[v.size()];
  mesh->mNormals = new aiVector3D[v.size()];
  mesh->mTextureCoords[0] = new aiVector3D[v.size()];
  mesh->mNumUVComponents[0] = 2;
  for (size_t i = 0; i < v.size(); ++i) {
    mesh->mVertices[i] = aiVector3D(v[i].p[0], v[i].p[1], v[i].p[2]);
    mesh->mNormals[i] = aiVector3D(v[i].n[0], v[i].n[1], v[i].n[2]);
    mesh->mTextureCoords[0][i] = aiVector3D(v[i].uv[0], v[i].uv[1], 0);
  }
  mesh->mNumFaces = unsigned(idx.size() / 3);
  mesh->mFaces = new aiFace[mesh->mNumFaces];
  for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
    mesh->mFaces[f].mNumIndices = 3;
    mesh->mFaces[f].mIndices = new unsigned[3]{idx[3 * f], idx[3 * f + 1], idx[3 * f + 2]};
  }
  return mesh;
}

aiMaterial* makeMaterial(const char* name, float r, float g, float b) {
  auto* m = new aiMaterial();
  aiString n(name);
  m->AddProperty(&n, AI_MATKEY_NAME);
  aiColor3D c(r, g, b);
  m->AddProperty(&c, 1, AI_MATKEY_COLOR_DIFFUSE);
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_FOLDER\n", argv[0]);
    return 2;
  }
  std::filesystem::path out(argv[1]);
  std::filesystem::create_directories(out);

  // A 0.4 x 0.3 x 0.3 crate body and a lid slab on top, two materials.
  std::vector<Vertex> bodyV, lidV;
  std::vector<unsigned> bodyI, lidI;
  const float bodyC[3] = {0, 0, 0.15f}, bodyH[3] = {0.2f, 0.15f, 0.15f};
  const float lidC[3] = {0, 0, 0.31f}, lidH[3] = {0.21f, 0.16f, 0.01f};
  addBox(bodyV, bodyI, bodyC, bodyH);
  addBox(lidV, lidI, lidC, lidH);

  aiScene scene;
  scene.mRootNode = new aiNode("crate");
  scene.mNumMaterials = 2;
  scene.mMaterials = new aiMaterial*[2]{makeMaterial("cardboard", 0.62f, 0.45f, 0.28f), makeMaterial("tape", 0.85f, 0.8f, 0.7f)};
  scene.mNumMeshes = 2;
  scene.mMeshes = new aiMesh*[2]{makeMesh("body", bodyV, bodyI, 0), makeMesh("lid", lidV, lidI, 1)};
  scene.mRootNode->mNumMeshes = 2;
  scene.mRootNode->mMeshes = new unsigned[2]{0, 1};

  Assimp::Exporter exporter;
  const std::pair<const char*, const char*> formats[] = {
      {"obj", "crate.obj"}, {"gltf2", "crate.gltf"}, {"glb2", "crate.glb"}, {"fbxa", "crate.fbx"},
      {"ply", "crate.ply"}, {"stl", "crate.stl"},    {"collada", "crate.dae"}};
  int failures = 0;
  for (const auto& [format, file] : formats) {
    if (exporter.Export(&scene, format, (out / file).string()) != AI_SUCCESS) {
      std::fprintf(stderr, "%s: %s\n", file, exporter.GetErrorString());
      ++failures;
    }
  }
  // assimp's FBX exporter writes UnitScaleFactor 1 (centimetres) for any
  // scene; these coordinates are metres, so say so (100 cm per unit), as
  // Blender does for a metre scene.
  std::filesystem::path fbx = out / "crate.fbx";
  std::stringstream text;
  text << std::ifstream(fbx).rdbuf();
  std::string content = text.str();
  for (const char* key : {"\"UnitScaleFactor\", \"double\", \"Number\", \"\", 1\n",
                          "\"OriginalUnitScaleFactor\", \"double\", \"Number\", \"\", 1\n"}) {
    std::string from(key), to = from.substr(0, from.size() - 2) + "100\n";
    if (size_t at = content.find(from); at != std::string::npos) content.replace(at, from.size(), to);
  }
  std::ofstream(fbx, std::ios::binary) << content;
  return failures ? 1 : 0;
}
