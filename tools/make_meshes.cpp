// Generates the small mesh files under scenes/props/ and tests/data/meshes/
// (made by this project; see third_party_notes/project-assets.md): a crate
// with two materials, written in every format sdgbehave reads, and the
// warehouse demo's props as GLB (two cartons, a bin, a pallet with slats, a
// drill-like tool), through assimp's exporters. Deterministic: running it again rewrites the same files.
//
//   build/release/tools/sdg_make_meshes <output folder>
#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include <array>
#include <cmath>
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

// A closed cylinder along X centred at c: `segments` side quads and two caps.
void addCylinderX(std::vector<Vertex>& v, std::vector<unsigned>& idx, const float c[3], float radius, float halfLength,
                  int segments) {
  const float pi = 3.14159265358979f;
  for (int s = 0; s < segments; ++s) {
    float a0 = 2 * pi * float(s) / float(segments), a1 = 2 * pi * float(s + 1) / float(segments);
    unsigned base = unsigned(v.size());
    for (float a : {a0, a1})
      for (float x : {-halfLength, halfLength}) {
        Vertex p{};
        p.p[0] = c[0] + x, p.p[1] = c[1] + radius * std::cos(a), p.p[2] = c[2] + radius * std::sin(a);
        p.n[1] = std::cos(a), p.n[2] = std::sin(a);
        p.uv[0] = a / (2 * pi), p.uv[1] = x > 0 ? 1.f : 0.f;
        v.push_back(p);
      }
    idx.insert(idx.end(), {base, base + 2, base + 3, base, base + 3, base + 1});
    for (float x : {-halfLength, halfLength}) {  // cap triangle fan pieces
      unsigned cb = unsigned(v.size());
      float sign = x > 0 ? 1.f : -1.f;
      for (float a : {-1.f, a0, a1}) {
        Vertex p{};
        p.p[0] = c[0] + x;
        p.p[1] = c[1] + (a < 0 ? 0 : radius * std::cos(a));
        p.p[2] = c[2] + (a < 0 ? 0 : radius * std::sin(a));
        p.n[0] = sign;
        v.push_back(p);
      }
      if (sign > 0) idx.insert(idx.end(), {cb, cb + 1, cb + 2});
      else idx.insert(idx.end(), {cb, cb + 2, cb + 1});
    }
  }
}

struct Part {
  const char* name;
  std::vector<Vertex> v;
  std::vector<unsigned> idx;
  unsigned material;
  void box(float cx, float cy, float cz, float hx, float hy, float hz) {
    const float c[3] = {cx, cy, cz}, h[3] = {hx, hy, hz};
    addBox(v, idx, c, h);
  }
};

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

// One prop: parts with their materials, exported as GLB.
bool exportProp(const std::filesystem::path& file, std::vector<Part> parts,
                const std::vector<std::pair<const char*, std::array<float, 3>>>& materials) {
  aiScene scene;
  scene.mRootNode = new aiNode(file.stem().string());
  scene.mNumMaterials = unsigned(materials.size());
  scene.mMaterials = new aiMaterial*[materials.size()];
  for (size_t i = 0; i < materials.size(); ++i)
    scene.mMaterials[i] = makeMaterial(materials[i].first, materials[i].second[0], materials[i].second[1],
                                       materials[i].second[2]);
  scene.mNumMeshes = unsigned(parts.size());
  scene.mMeshes = new aiMesh*[parts.size()];
  scene.mRootNode->mNumMeshes = unsigned(parts.size());
  scene.mRootNode->mMeshes = new unsigned[parts.size()];
  for (size_t i = 0; i < parts.size(); ++i) {
    scene.mMeshes[i] = makeMesh(parts[i].name, parts[i].v, parts[i].idx, parts[i].material);
    scene.mRootNode->mMeshes[i] = unsigned(i);
  }
  Assimp::Exporter exporter;
  if (exporter.Export(&scene, "glb2", file.string()) == AI_SUCCESS) return true;
  std::fprintf(stderr, "%s: %s\n", file.string().c_str(), exporter.GetErrorString());
  return false;
}

// The warehouse demo's props, origin at the bottom centre, metres, +Z up.
int writeWarehouseProps(const std::filesystem::path& out) {
  int failures = 0;
  const std::array<float, 3> cardboard{0.62f, 0.45f, 0.28f}, tape{0.85f, 0.8f, 0.7f};
  {  // A closed carton with a tape strip over the seam of its top flaps.
    Part body{"body", {}, {}, 0}, strip{"tape", {}, {}, 1};
    body.box(0, 0, 0.15f, 0.2f, 0.15f, 0.15f);
    body.box(-0.1f, 0, 0.3025f, 0.0995f, 0.15f, 0.0025f);  // two top flaps meeting in the middle
    body.box(0.1f, 0, 0.3025f, 0.0995f, 0.15f, 0.0025f);
    strip.box(0, 0, 0.306f, 0.025f, 0.152f, 0.001f);
    failures += !exportProp(out / "cardbox_a.glb", {body, strip}, {{"cardboard", cardboard}, {"tape", tape}});
  }
  {  // An open carton: four flaps standing up around the top edge.
    Part body{"body", {}, {}, 0}, flaps{"flaps", {}, {}, 0};
    body.box(0, 0, 0.125f, 0.25f, 0.175f, 0.125f);
    flaps.box(0, 0.1725f, 0.3f, 0.25f, 0.0025f, 0.05f);
    flaps.box(0, -0.1725f, 0.3f, 0.25f, 0.0025f, 0.05f);
    flaps.box(0.2475f, 0, 0.3f, 0.0025f, 0.17f, 0.05f);
    flaps.box(-0.2475f, 0, 0.3f, 0.0025f, 0.17f, 0.05f);
    failures += !exportProp(out / "cardbox_b.glb", {body, flaps}, {{"cardboard", {0.55f, 0.4f, 0.25f}}});
  }
  {  // A small open plastic bin: floor, four walls and a rim.
    Part bin{"bin", {}, {}, 0};
    bin.box(0, 0, 0.005f, 0.15f, 0.1f, 0.005f);
    bin.box(0, 0.095f, 0.075f, 0.15f, 0.005f, 0.075f);
    bin.box(0, -0.095f, 0.075f, 0.15f, 0.005f, 0.075f);
    bin.box(0.145f, 0, 0.075f, 0.005f, 0.1f, 0.075f);
    bin.box(-0.145f, 0, 0.075f, 0.005f, 0.1f, 0.075f);
    failures += !exportProp(out / "bin.glb", {bin}, {{"blue_plastic", {0.1f, 0.3f, 0.7f}}});
  }
  {  // A 1.2 x 1.0 m pallet: 7 top slats, 3 stringer blocks rows, 3 bottom boards.
    Part wood{"pallet", {}, {}, 0};
    for (int i = 0; i < 7; ++i) wood.box(-0.54f + 0.18f * float(i), 0, 0.135f, 0.05f, 0.5f, 0.011f);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) wood.box(-0.55f + 0.55f * float(i), -0.45f + 0.45f * float(j), 0.075f, 0.05f, 0.05f, 0.049f);
    for (int i = 0; i < 3; ++i) wood.box(-0.55f + 0.55f * float(i), 0, 0.013f, 0.05f, 0.5f, 0.011f);
    // Cross boards under the slats hold the blocks together.
    for (int j = 0; j < 3; ++j) wood.box(0, -0.45f + 0.45f * float(j), 0.1135f, 0.6f, 0.05f, 0.0105f);
    failures += !exportProp(out / "pallet.glb", {wood}, {{"pallet_wood", {0.6f, 0.45f, 0.3f}}});
  }
  {  // A drill-like shape: motor body, chuck, bit, handle and battery.
    Part shell{"shell", {}, {}, 0}, metal{"metal", {}, {}, 1}, dark{"grip", {}, {}, 2};
    const float bodyC[3] = {0, 0, 0.2f}, chuckC[3] = {0.13f, 0, 0.2f}, bitC[3] = {0.2f, 0, 0.2f};
    addCylinderX(shell.v, shell.idx, bodyC, 0.04f, 0.1f, 24);
    addCylinderX(metal.v, metal.idx, chuckC, 0.022f, 0.03f, 16);
    addCylinderX(metal.v, metal.idx, bitC, 0.004f, 0.045f, 8);
    dark.box(-0.03f, 0, 0.11f, 0.025f, 0.02f, 0.06f);
    shell.box(-0.03f, 0, 0.03f, 0.06f, 0.04f, 0.03f);
    failures += !exportProp(out / "drill.glb", {shell, metal, dark},
                            {{"drill_red", {0.75f, 0.12f, 0.08f}}, {"steel", {0.7f, 0.7f, 0.72f}}, {"grip", {0.08f, 0.08f, 0.08f}}});
  }
  return failures;
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
  failures += writeWarehouseProps(out);
  return failures ? 1 : 0;
}
