#include "scene_io/usd_mesh_asset.h"

#include <filesystem>

#include "assets/inline_mesh.h"
#include "assets/mesh_loader.h"
#include "core/diagnostics.h"
#include "scene_io/usd_import.h"
#include "usd/layer_io.h"

namespace sdg {
namespace {

// The part a Mesh prim draws with: its bound Material's inputs, else its
// displayColor and displayOpacity, per vertex when it has them (as
// render_list.cpp reads them for a Mesh on the stage).
MeshPart partFor(const Stage& stage, const Prim& mesh) {
  MeshPart part;
  part.hasMaterial = true;
  const Prim* material = mesh.material() ? stage.find(mesh.material()->path) : nullptr;
  if (!material) {
    if (const Value* c = mesh.value("primvars:displayColor")) part.baseColor = c->get<Vec3f>();
    const bool perVertexColor = mesh.findAttribute("primvars:displayColor:faceVarying") != nullptr;
    const bool perVertexOpacity = mesh.findAttribute("primvars:displayOpacity:faceVarying") != nullptr;
    const float opacity = mesh.getFloat("primvars:displayOpacity");
    if (perVertexColor) part.baseColor = Vec3f(1.0f, 1.0f, 1.0f);
    part.vertexColors = perVertexColor || perVertexOpacity;
    if (perVertexOpacity || opacity < 1.0f) {
      part.opacity = OpacitySource::Constant;
      part.opacityConstant = perVertexOpacity ? 1.0f : opacity;
    }
    return part;
  }
  part.baseColor = material->value("inputs:diffuse_color_constant")->get<Vec3f>();
  part.maps.baseColor = material->getString("inputs:diffuse_texture");
  part.roughness = material->getFloat("inputs:reflection_roughness_constant");
  part.metallic = material->getFloat("inputs:metallic_constant");
  return part;
}

// `m` transformed by `world` and appended to `out`, its triangles as one part.
void append(MeshData& out, const MeshData& m, const Matrix4d& world, MeshPart part) {
  const Eigen::Matrix3d normalMatrix = world.topLeftCorner<3, 3>().inverse().transpose();
  const uint32_t base = uint32_t(out.positions.size());
  for (const Vec3f& p : m.positions) out.positions.push_back((world * p.cast<double>().homogeneous()).head<3>().cast<float>());
  for (const Vec3f& n : m.normals) out.normals.push_back((normalMatrix * n.cast<double>()).normalized().cast<float>());
  for (size_t i = 0; i < m.positions.size(); ++i)
    out.uvs.push_back(i < m.uvs.size() ? m.uvs[i] : Eigen::Vector2f(0.0f, 0.0f));
  // Colours for every vertex once any mesh has them (white for the others).
  if (!m.colors.empty() || !out.colors.empty()) {
    out.colors.resize(base, Eigen::Vector4f::Ones());
    for (size_t i = 0; i < m.positions.size(); ++i)
      out.colors.push_back(i < m.colors.size() ? m.colors[i] : Eigen::Vector4f::Ones());
  }
  part.firstIndex = uint32_t(out.indices.size());
  part.indexCount = uint32_t(m.indices.size());
  for (uint32_t i : m.indices) out.indices.push_back(base + i);
  out.parts.push_back(part);
}

// A mesh file's whole mesh (every part, with its own material) under `world`.
void appendFile(MeshData& out, const MeshData& m, const Matrix4d& world) {
  MeshData slice;
  slice.positions = m.positions;
  slice.normals = m.normals;
  slice.uvs = m.uvs;
  slice.colors = m.colors;
  for (const MeshPart& part : m.parts) {
    slice.indices.assign(m.indices.begin() + part.firstIndex, m.indices.begin() + part.firstIndex + part.indexCount);
    append(out, slice, world, part);
  }
}

// How deep USD mesh files may name mesh files that are USD files again.
constexpr int kMaxNestedMeshFiles = 8;
thread_local int gNestedMeshFiles = 0;

}  // namespace

MeshData loadUsdMeshAsset(const std::string& path, const std::string& submesh) {
  usd::ComposedStage composed;
  try {
    composed = usd::composeStage(path, [](const std::string& id) { return usd::readLayerFile(id); }, {});
  } catch (const usd::UsdError& e) {
    throw RunError(path + ": cannot read the USD mesh: " + e.what());
  }
  Stage stage;
  Diagnostics diag;
  UsdImportReport report;
  UsdImportOptions options;
  options.runDefaults = false;
  options.builtinsForIsaacScripts = false;
  const BehaviorCatalog noBehaviors;
  importUsdPrims(composed, "/", stage, "/", noBehaviors, options, report, diag);
  for (const Diagnostic& d : diag.all())
    if (d.severity == Severity::Error) throw RunError(path + ": cannot read the USD mesh: " + d.loc.str() + ": " + d.message);
  MeshData out;
  stage.traverse([&](const Prim& prim) {
    if (prim.type() != PrimType::Mesh) return;
    if (!submesh.empty() && prim.path() != submesh && !prim.path().starts_with(submesh + "/")) return;
    // A Mesh prim showing a mesh file (export-usd's sdgbehave:asset): that
    // file's mesh, relative to this file's folder.
    if (const Value* file = prim.value("asset"); file && !file->get<std::string>().empty()) {
      std::filesystem::path named(file->get<std::string>());
      if (named.is_relative()) named = std::filesystem::path(path).parent_path() / named;
      std::error_code ec;
      if (!std::filesystem::is_regular_file(named, ec))
        throw RunError(path + ": " + prim.path() + " names the mesh file " + named.string() + ", which is not a file");
      if (gNestedMeshFiles >= kMaxNestedMeshFiles)
        throw RunError(path + ": mesh files name each other more than " + std::to_string(kMaxNestedMeshFiles) +
                       " deep (a cycle?)");
      ++gNestedMeshFiles;
      try {
        appendFile(out, loadMeshFile(named.lexically_normal().string(), ""), stage.worldMatrix(prim));
      } catch (...) {
        --gNestedMeshFiles;
        throw;
      }
      --gNestedMeshFiles;
      return;
    }
    // Drawn as authored: a mesh file's key carries no subdivision level.
    std::shared_ptr<const InlineMesh> mesh = inlineMeshOf(prim, 0);
    if (!mesh) return;
    append(out, triangulateInlineMesh(*mesh, path + " " + prim.path()), stage.worldMatrix(prim), partFor(stage, prim));
  });
  if (out.indices.empty())
    throw RunError(path + ": no Mesh prim with faces" + (submesh.empty() ? "" : " at or under " + submesh) +
                   " in the USD file");
  out.updateBounds();
  return out;
}

void registerUsdMeshAssets() { setUsdMeshReader(&loadUsdMeshAsset); }

}  // namespace sdg
