#include "render/pathtrace/gpu/gpu_scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "assets/image.h"
#include "assets/mesh_source.h"
#include "assets/texture_source.h"
#include "core/diagnostics.h"
#include "render/pathtrace/gpu/gl_compute.h"

namespace sdg {
namespace {

constexpr size_t kMaxCachedDomes = 8;  // as in the CPU tracer
constexpr uint32_t kMaxTriangleIndex = 1u << 24;  // stored as a float in the kernel's triangles

void rows(const Eigen::Matrix3d& linear, const Vec3d& translation, float* out) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out[4 * r + c] = float(linear(r, c));
    out[4 * r + 3] = float(translation[r]);
  }
}

void put3(float* out, const Vec3f& v, float w) {
  out[0] = v.x();
  out[1] = v.y();
  out[2] = v.z();
  out[3] = w;
}

// A triangle as the affine map that takes it to the unit triangle (Woop,
// Benthin and Wald 2013's "unit triangle" form): rows u, v and z of the
// inverse of [p1 - p0, p2 - p0, normal | p0]. The kernel's test is then
// three dot products a row: z gives the distance, u and v Embree's
// barycentrics, with no cross product per ray. Worked out in double; a
// degenerate triangle gets zero rows, which no ray meets (0 / 0 is NaN).
struct UnitTriangle {
  float rows[12];
};
UnitTriangle unitTriangle(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2) {
  const Vec3d a = p0.cast<double>(), e1 = (p1 - p0).cast<double>(), e2 = (p2 - p0).cast<double>();
  const Vec3d n = e1.cross(e2);
  UnitTriangle unit{};
  Eigen::Matrix3d columns;
  columns << e1, e2, n;
  const double det = columns.determinant();
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return unit;
  const Eigen::Matrix3d inverse = columns.inverse();
  rows(inverse, -(inverse * a), unit.rows);
  return unit;
}

int32_t opacityCode(OpacitySource source) {
  switch (source) {
    case OpacitySource::None: return 0;
    case OpacitySource::Constant: return 1;
    case OpacitySource::OpacityMap: return 2;
    case OpacitySource::BaseColorAlpha: return 3;
  }
  return 0;
}

}  // namespace

struct GpuSceneData::Mesh {
  MeshData data;
  uint32_t record = 0;
  bool empty = true;
};

GpuSceneData::GpuSceneData(const AssetResolver& assets) : assets_(assets), textureCache_(assets) {
  // The sRGB decode, computed as pt_textures.cpp's table is.
  for (int k = 0; k < 256; ++k) tables.push_back(srgbToLinear(float(k) / 255.0f));
}

GpuSceneData::~GpuSceneData() = default;

uint32_t GpuSceneData::meshFor(const RenderItem& item) {
  auto found = meshIndex_.find(item.meshId);
  if (found != meshIndex_.end()) return found->second;
  auto mesh = std::make_unique<Mesh>();
  mesh->data = meshDataFor(item.mesh, assets_, item.primPath);
  textureCache_.addEmbedded(mesh->data.embeddedImages);
  mesh->data.embeddedImages.clear();
  MeshData& d = mesh->data;
  // As embree_scene.cpp: indices beyond the vertices leave the mesh empty.
  const uint32_t vertexCount = uint32_t(d.positions.size());
  if (std::any_of(d.indices.begin(), d.indices.end(), [&](uint32_t i) { return i >= vertexCount; })) d.indices.clear();
  d.indices.resize(d.triangleCount() * 3);
  const size_t triangleCount = d.triangleCount();
  if (triangleCount >= kMaxTriangleIndex)
    throw GpuUnavailable("GPU path tracer: " + item.primPath + "'s mesh has " + std::to_string(triangleCount) +
                         " triangles; the GPU tracer takes at most 16777215 per mesh");

  GpuMeshRecord record{};
  record.bases[0] = int32_t(meshNodes.size());
  record.bases[1] = int32_t(triangles.size() / 16);
  record.bases[2] = int32_t(indices.size() / 4);
  record.bases[3] = int32_t(vertices.size() / 8);
  const bool hasNormals = d.normals.size() == d.positions.size(), hasUvs = d.uvs.size() == d.positions.size();
  record.flags[0] = hasNormals;
  record.flags[1] = hasUvs;
  for (size_t v = 0; v < d.positions.size(); ++v) {
    const Vec3f n = hasNormals ? d.normals[v] : Vec3f::Zero();
    const Eigen::Vector2f uv = hasUvs ? d.uvs[v] : Eigen::Vector2f::Zero();
    const float packed[8] = {d.positions[v].x(), d.positions[v].y(), d.positions[v].z(), uv.x(),
                             n.x(), n.y(), n.z(), uv.y()};
    vertices.insert(vertices.end(), packed, packed + 8);
  }
  if (d.colors.size() == d.positions.size() && !d.colors.empty()) {
    record.flags[3] = int32_t(vertices.size() / 4) + 1;
    for (const Eigen::Vector4f& c : d.colors) vertices.insert(vertices.end(), c.data(), c.data() + 4);
    vertices.resize((vertices.size() + 7) / 8 * 8, 0.0f);  // the next mesh's base counts in 8s
  }
  // Each triangle's part: the part whose range starts at or before it (embree_scene.cpp's rule).
  std::vector<std::pair<uint32_t, uint32_t>> starts;
  for (size_t p = 0; p < d.parts.size(); ++p) starts.emplace_back(d.parts[p].firstIndex / 3, uint32_t(p));
  std::sort(starts.begin(), starts.end());
  std::vector<Eigen::AlignedBox3f> boxes(triangleCount);
  for (size_t t = 0; t < triangleCount; ++t) {
    const uint32_t* tri = &d.indices[3 * t];
    auto above = std::upper_bound(starts.begin(), starts.end(), std::make_pair(uint32_t(t), UINT32_MAX));
    const uint32_t part = above == starts.begin() ? (starts.empty() ? 0 : starts[0].second) : std::prev(above)->second;
    indices.insert(indices.end(), {tri[0], tri[1], tri[2], part});
    boxes[t].setEmpty();
    for (int k = 0; k < 3; ++k) boxes[t].extend(d.positions[tri[k]]);
  }
  const GpuBvh bvh = builder_.build(boxes, false);
  record.flags[2] = bvh.rootLink;
  meshNodes.insert(meshNodes.end(), bvh.nodes.begin(), bvh.nodes.end());
  for (uint32_t t : bvh.order) {
    const UnitTriangle unit = unitTriangle(d.positions[d.indices[3 * size_t(t)]],
                                           d.positions[d.indices[3 * size_t(t) + 1]],
                                           d.positions[d.indices[3 * size_t(t) + 2]]);
    triangles.insert(triangles.end(), unit.rows, unit.rows + 12);
    const float id[4] = {float(t), 0.0f, 0.0f, 0.0f};
    triangles.insert(triangles.end(), id, id + 4);
  }
  mesh->record = uint32_t(meshes.size());
  mesh->empty = triangleCount == 0;
  meshes.push_back(record);
  meshesChanged = true;
  const uint32_t index = uint32_t(meshData_.size());
  meshData_.push_back(std::move(mesh));
  meshIndex_.emplace(item.meshId, index);
  return index;
}

int32_t GpuSceneData::textureIndex(const PtTexture* texture) {
  if (!texture) return -1;
  auto found = textureSlots_.find(texture);
  if (found != textureSlots_.end()) return found->second;
  const ImageRgba8& image = texture->image();
  const int32_t slot = int32_t(textureTable.size() / 4);
  textureTable.insert(textureTable.end(),
                      {int32_t(texels.size()), int32_t(image.width), int32_t(image.height), texture->srgb() ? 1 : 0});
  const size_t count = size_t(image.width) * image.height;
  const size_t first = texels.size();
  texels.resize(first + count);
  std::memcpy(&texels[first], image.pixels.data(), count * 4);  // RGBA bytes: little-endian words, R lowest
  textureSlots_.emplace(texture, slot);
  texelsChanged = true;
  return slot;
}

void GpuSceneData::update(const RenderList& list) {
  materials.clear();
  std::vector<GpuInstanceRecord> frameInstances;
  std::vector<Eigen::AlignedBox3f> boxes;
  std::vector<double> key;
  bounds.setEmpty();
  for (size_t i = 0; i < list.items.size(); ++i) {
    const RenderItem& item = list.items[i];
    const Mesh& mesh = *meshData_[meshFor(item)];
    const int32_t firstMaterial = int32_t(materials.size());
    bool cutOut = false;
    const std::vector<MeshPart> defaultPart(mesh.data.parts.empty() ? 1 : 0);
    for (const MeshPart& part : mesh.data.parts.empty() ? defaultPart : mesh.data.parts) {
      const SurfaceMaterial m = resolveSurfaceMaterial(item, part, textureCache_);
      cutOut = cutOut || m.cutOut();
      GpuMaterialRecord r{};
      put3(r.baseColor, m.baseColor, m.roughness);
      const float scalars[4] = {m.metallic, m.roughnessInfluence, m.metallicInfluence, m.normalScale};
      std::copy(scalars, scalars + 4, r.scalars);
      const float opacity[4] = {m.opacityConstant, m.opacityCutoff, m.cosRotate, m.sinRotate};
      std::copy(opacity, opacity + 4, r.opacity);
      const float placement[4] = {m.textureScale.x(), m.textureScale.y(), m.specularLevel, 0.0f};
      std::copy(placement, placement + 4, r.placement);
      const int32_t maps[4] = {textureIndex(m.baseMap), textureIndex(m.roughnessMap), textureIndex(m.metallicMap),
                               textureIndex(m.normalMap)};
      std::copy(maps, maps + 4, r.maps);
      const int32_t info[4] = {textureIndex(m.opacityMap), m.roughnessChannel, m.metallicChannel, opacityCode(m.opacity)};
      std::copy(info, info + 4, r.mapInfo);
      r.modes[0] = m.partMaterial;
      r.modes[1] = m.triplanar;
      r.modes[2] = m.vertexColors;
      materials.push_back(r);
    }
    const Eigen::Matrix3d linear = item.worldFromLocal.block<3, 3>(0, 0);
    const double det = linear.determinant();
    if (mesh.empty || !std::isfinite(det) || std::abs(det) < 1e-30) continue;  // nothing to hit, as on the CPU
    const Vec3d translation = item.worldFromLocal.block<3, 1>(0, 3);
    GpuInstanceRecord r{};
    rows(linear, translation, r.world);
    const Eigen::Matrix3d inverse = linear.inverse();
    rows(inverse, -(inverse * translation), r.local);
    rows(inverse.transpose(), Vec3d::Zero(), r.normal);
    const int32_t ids[4] = {int32_t(mesh.record), firstMaterial, int32_t(materials.size()) - firstMaterial,
                            int32_t(item.instanceId)};
    std::copy(ids, ids + 4, r.ids);
    r.flags[0] = cutOut;
    frameInstances.push_back(r);
    Eigen::AlignedBox3f box;
    box.setEmpty();
    const Eigen::Matrix3f linearF = linear.cast<float>();
    const Vec3f translationF = translation.cast<float>();
    if (!mesh.data.bounds.isEmpty())
      for (int c = 0; c < 8; ++c)
        box.extend(Vec3f(linearF * mesh.data.bounds.corner(Eigen::AlignedBox3f::CornerType(c)) + translationF));
    boxes.push_back(box);
    bounds.extend(box);
    key.push_back(double(mesh.record));
    for (int k = 0; k < 16; ++k) key.push_back(item.worldFromLocal.data()[k]);
    key.insert(key.end(), {double(firstMaterial), double(ids[2]), double(item.instanceId), double(cutOut)});
  }
  // The top level: rebuilt only when an instance changed.
  if (key != lastTransforms_ || instances.empty() != frameInstances.empty()) {
    const GpuBvh top = builder_.build(boxes, false);
    topNodes = top.nodes;
    topRoot = top.rootLink;
    instances.clear();
    for (uint32_t i : top.order) instances.push_back(frameInstances[i]);
    lastTransforms_ = std::move(key);
    instancesChanged = true;
  }
  packLights(list);
  kernelFeatures = featuresInUse();
}

// From the packed records alone, so a frame's kernel is a function of the
// frame's stage (whatever came before it: shards and reruns agree).
uint32_t GpuSceneData::featuresInUse() const {
  uint32_t features = anyLobeMultiplier ? kGpuLobeMultipliers : 0u;
  for (const GpuMaterialRecord& m : materials) {
    if (m.mapInfo[3] != 0) features |= kGpuOpacity;
    if (m.maps[3] >= 0) features |= kGpuNormalMaps;
    if (m.modes[1] != 0) features |= kGpuTriplanar;
    if (m.maps[0] >= 0) features |= kGpuBaseColorMaps;
    if (m.maps[1] >= 0 || m.maps[2] >= 0) features |= kGpuSurfaceMaps;
    if (m.modes[2] != 0) features |= kGpuVertexColors;
  }
  for (const GpuInstanceRecord& i : instances)
    if (i.flags[0]) features |= kGpuOpacity;
  for (const GpuLightRecord& l : lights) {
    if (l.info[2] != 0) features |= kGpuDomeMaps;
    switch (LightKind(l.info[0])) {
      case LightKind::Sphere: features |= kGpuSphereLights; break;
      case LightKind::Rect:
      case LightKind::Disk:
      case LightKind::Cylinder: features |= kGpuShapeLights; break;
      case LightKind::Distant: features |= kGpuDistantLights; break;
      case LightKind::Dome: features |= kGpuDomeLights; break;
    }
  }
  return features;
}

void GpuSceneData::packLights(const RenderList& list) {
  PtLights built;
  built.build(list, bounds, [&](const RenderLight& light) -> const PtDomeMap* {
    auto it = domes_.find(light.texture);
    if (it != domes_.end()) return it->second.get();
    ImageRgbaF map = loadDomeMap(light.texture, assets_, light.path);
    if (domes_.size() >= kMaxCachedDomes) {
      if (domes_.begin()->second.get() == uploadedDome_) uploadedDome_ = nullptr;
      domes_.erase(domes_.begin());
    }
    return domes_.emplace(light.texture, std::make_unique<PtDomeMap>(std::move(map))).first->second.get();
  });
  lights.clear();
  anyLobeMultiplier = built.anyLobeMultiplier();
  const PtDomeMap* domeMap = nullptr;
  for (const PtLights::Light& l : built.lights()) {
    GpuLightRecord r{};
    const int32_t info[4] = {int32_t(l.kind), l.delta ? 1 : 0, l.map ? 1 : 0, l.point ? 1 : 0};
    std::copy(info, info + 4, r.info);
    put3(r.radiancePick, l.radiance, l.pick);
    put3(r.positionRadius, l.position, l.radius);
    put3(r.axisXWidth, l.axisX, l.width);
    put3(r.axisYHeight, l.axisY, l.height);
    put3(r.axisZLength, l.axisZ, l.length);
    put3(r.emitArea, l.emit, l.area);
    put3(r.toLightCone, l.toLight, l.oneMinusCos);
    put3(r.misc, Vec3f(l.sin2Half, l.mapProbability, l.diffuse), l.specular);
    put3(r.mapScale, l.mapScale, 0.0f);
    put3(r.ambient, l.ambient, 0.0f);
    for (int row = 0; row < 3; ++row) put3(r.domeFromWorld + 4 * row, Vec3f(l.domeFromWorld.row(row).transpose()), 0.0f);
    if (l.map) domeMap = l.map;
    lights.push_back(r);
  }
  // The dome's texels and tables, when the map changed; the pick cdf after them, every frame.
  if (domeMap != uploadedDome_) {
    tables.resize(256);
    domeTexels.clear();
    if (domeMap) {
      const EnvironmentSampler& s = domeMap->sampler;
      const size_t words = size_t(domeMap->image.width) * domeMap->image.height * 4;
      domeTexels.resize(words);
      std::memcpy(domeTexels.data(), domeMap->image.pixels.data(), words * sizeof(float));
      domeTables[0] = int32_t(tables.size());
      tables.insert(tables.end(), s.rowCdf().begin(), s.rowCdf().end());
      domeTables[1] = int32_t(tables.size());
      tables.insert(tables.end(), s.columnCdf().begin(), s.columnCdf().end());
      domeTables[2] = int32_t(tables.size());
      for (double c : s.rowCosines()) tables.push_back(float(c));
      domeTables[3] = int32_t(tables.size());
      tables.insert(tables.end(), s.texelSolidAngles().begin(), s.texelSolidAngles().end());
    }
    uploadedDome_ = domeMap;
    texelsChanged = true;
    tablesChanged = true;
  }
  dome[0] = uploadedDome_ ? int32_t(uploadedDome_->image.width) : 0;
  dome[1] = uploadedDome_ ? int32_t(uploadedDome_->image.height) : 0;
  dome[2] = int32_t(texels.size());  // the dome's texels follow the textures'
  tables.resize(uploadedDome_ ? size_t(domeTables[3]) + uploadedDome_->image.height : 256);
  dome[3] = int32_t(tables.size());
  tables.insert(tables.end(), built.pickCdf().begin(), built.pickCdf().end());
  tables.resize(size_t(dome[3]) + lights.size() + 1, 0.0f);  // the cdf's count + 1 entries, whatever it holds
  // Then the lights a ray can meet, their number and their indices (as
  // floats, exact below 2^24), so the kernel's intersect and block loops
  // skip the others (distant and dome lights, spheres treated as points)
  // without loading them.
  const size_t hittableAt = tables.size();
  tables.push_back(0.0f);
  for (size_t i = 0; i < lights.size(); ++i) {
    const LightKind kind = LightKind(lights[i].info[0]);
    const bool point = lights[i].info[3] != 0;
    if ((kind == LightKind::Sphere && !point) || kind == LightKind::Rect || kind == LightKind::Disk ||
        kind == LightKind::Cylinder)
      tables.push_back(float(i));
  }
  tables[hittableAt] = float(tables.size() - hittableAt - 1);
}

}  // namespace sdg
