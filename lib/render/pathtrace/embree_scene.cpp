#include "render/pathtrace/embree_scene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cstring>
#include <string>

#include "core/diagnostics.h"

namespace sdg {
namespace {

// The context handed to rtcIntersect1 / rtcOccluded1, extended with the
// frame's cut-out test: Embree passes it on to the filter functions.
struct FilterContext {
  RTCIntersectContext base;
  const CutOutTest* cutOuts;
};

// Rejects candidate hits where the cut-out test finds the surface clear.
// Embree calls it for every candidate on the filtered BVHs, in any order;
// the closest accepted hit is the same whatever that order.
void cutOutFilter(const RTCFilterFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const FilterContext*>(args->context);
  if (!context->cutOuts) return;
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const uint32_t instance = RTCHitN_instID(args->hit, args->N, i, 0);
    const uint32_t triangle = RTCHitN_primID(args->hit, args->N, i);
    const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    if (!context->cutOuts->opaqueAt(instance, triangle, u, v)) args->valid[i] = 0;
  }
}

void initRay(const PtRay& in, RTCRay& ray) {
  ray.org_x = in.origin.x();
  ray.org_y = in.origin.y();
  ray.org_z = in.origin.z();
  ray.tnear = in.tMin;
  ray.dir_x = in.direction.x();
  ray.dir_y = in.direction.y();
  ray.dir_z = in.direction.z();
  ray.time = 0.0f;
  ray.tfar = in.tMax;
  ray.mask = 0xffffffffu;
  ray.id = 0;
  ray.flags = 0;
}

}  // namespace

struct EmbreeScene::Impl {
  RTCDevice device = nullptr;
  RTCScene top = nullptr;
  std::string error;  // the first error Embree reported since the last check

  void check(const char* what) {
    if (error.empty()) return;
    std::string message = std::string("path tracer: Embree failed while ") + what + ": " + error;
    error.clear();
    throw RunError(message);
  }
};

struct EmbreeScene::Mesh {
  MeshData data;
  RTCScene plain = nullptr;     // the BVH every opaque instance shares
  RTCScene filtered = nullptr;  // the same triangles with the cut-out filter, built on first need
  std::vector<uint32_t> partFirstTriangle;  // ascending
  std::vector<uint32_t> partOfRange;        // the part whose range starts there
};

struct EmbreeScene::Instance {
  uint32_t mesh = 0;
  Eigen::Matrix3f linear;  // world from local, without the translation
  Vec3f translation;
  Eigen::Matrix3f normalMatrix;  // inverse transpose of `linear`
};

EmbreeScene::EmbreeScene() : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice("threads=1,set_affinity=0");
  if (!impl_->device) throw RunError("path tracer: cannot create the Embree device (error " +
                                     std::to_string(int(rtcGetDeviceError(nullptr))) + ")");
  rtcSetDeviceErrorFunction(
      impl_->device,
      [](void* user, RTCError, const char* message) {
        auto* impl = static_cast<Impl*>(user);
        if (impl->error.empty()) impl->error = message ? message : "unknown error";
      },
      impl_.get());
  bounds_.setEmpty();
}

EmbreeScene::~EmbreeScene() {
  if (impl_->top) rtcReleaseScene(impl_->top);
  for (auto& mesh : meshes_) {
    if (mesh->plain) rtcReleaseScene(mesh->plain);
    if (mesh->filtered) rtcReleaseScene(mesh->filtered);
  }
  rtcReleaseDevice(impl_->device);
}

namespace {

// A BVH of one triangle geometry holding `data`'s triangles; with `filter`
// the cut-out filter runs on its candidate hits.
RTCScene buildTriangleBvh(RTCDevice device, const MeshData& data, bool filter, void* user) {
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  // Embree's own buffers: they come with the padding its SIMD loads need.
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), data.positions.size()));
  auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(uint32_t), data.triangleCount()));
  if (vertices && indices) {
    for (size_t i = 0; i < data.positions.size(); ++i)
      for (int k = 0; k < 3; ++k) vertices[3 * i + size_t(k)] = data.positions[i][k];
    std::memcpy(indices, data.indices.data(), data.triangleCount() * 3 * sizeof(uint32_t));
  }
  if (filter) {
    rtcSetGeometryIntersectFilterFunction(geometry, cutOutFilter);
    rtcSetGeometryOccludedFilterFunction(geometry, cutOutFilter);
  }
  rtcSetGeometryUserData(geometry, user);
  rtcCommitGeometry(geometry);
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
  rtcAttachGeometryByID(scene, geometry, 0);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene);
  return scene;
}

}  // namespace

uint32_t EmbreeScene::addMesh(MeshData data) {
  auto mesh = std::make_unique<Mesh>();
  mesh->data = std::move(data);
  MeshData& d = mesh->data;
  // Indices beyond the vertices would send Embree out of bounds: such a
  // file is broken, and its mesh is left empty rather than crash the run.
  const uint32_t vertexCount = uint32_t(d.positions.size());
  if (std::any_of(d.indices.begin(), d.indices.end(), [&](uint32_t i) { return i >= vertexCount; })) d.indices.clear();
  d.indices.resize(d.triangleCount() * 3);
  // Triangle -> part, by the parts' first triangles in ascending order.
  std::vector<std::pair<uint32_t, uint32_t>> starts;
  for (size_t p = 0; p < d.parts.size(); ++p) starts.emplace_back(d.parts[p].firstIndex / 3, uint32_t(p));
  std::sort(starts.begin(), starts.end());
  for (const auto& [first, part] : starts) {
    mesh->partFirstTriangle.push_back(first);
    mesh->partOfRange.push_back(part);
  }
  if (d.triangleCount() > 0) {
    mesh->plain = buildTriangleBvh(impl_->device, d, false, mesh.get());
    impl_->check("building a mesh's BVH");
  }
  meshes_.push_back(std::move(mesh));
  return uint32_t(meshes_.size() - 1);
}

const MeshData& EmbreeScene::mesh(uint32_t index) const { return meshes_[index]->data; }

void EmbreeScene::buildFilteredBvh(Mesh& mesh) {
  if (mesh.filtered || mesh.data.triangleCount() == 0) return;
  mesh.filtered = buildTriangleBvh(impl_->device, mesh.data, true, &mesh);
  impl_->check("building a cut-out mesh's BVH");
}

void EmbreeScene::setInstances(const std::vector<SceneInstance>& instances) {
  if (impl_->top) rtcReleaseScene(impl_->top);
  impl_->top = rtcNewScene(impl_->device);
  rtcSetSceneFlags(impl_->top, RTC_SCENE_FLAG_ROBUST);
  instances_.assign(instances.size(), Instance{});
  bounds_.setEmpty();
  for (size_t i = 0; i < instances.size(); ++i) {
    const SceneInstance& in = instances[i];
    Mesh& mesh = *meshes_[in.mesh];
    Instance& out = instances_[i];
    out.mesh = in.mesh;
    const Eigen::Matrix3d linear = in.worldFromLocal.block<3, 3>(0, 0);
    const double det = linear.determinant();
    if (!mesh.plain || !std::isfinite(det) || std::abs(det) < 1e-30) continue;
    out.linear = linear.cast<float>();
    out.translation = in.worldFromLocal.block<3, 1>(0, 3).cast<float>();
    out.normalMatrix = linear.inverse().transpose().cast<float>();
    if (in.cutOut) buildFilteredBvh(mesh);
    RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(geometry, in.cutOut ? mesh.filtered : mesh.plain);
    Eigen::Matrix<float, 3, 4> xfm;  // column major, as Embree reads it
    xfm.block<3, 3>(0, 0) = out.linear;
    xfm.col(3) = out.translation;
    rtcSetGeometryTransform(geometry, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm.data());
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(impl_->top, geometry, unsigned(i));
    rtcReleaseGeometry(geometry);
    // World bounds: the transformed corners of the mesh's box.
    const Eigen::AlignedBox3f& box = mesh.data.bounds;
    if (!box.isEmpty())
      for (int c = 0; c < 8; ++c)
        bounds_.extend(Vec3f(out.linear * box.corner(Eigen::AlignedBox3f::CornerType(c)) + out.translation));
  }
  rtcCommitScene(impl_->top);
  impl_->check("building the frame's instances");
}

bool EmbreeScene::intersect(const PtRay& ray, const CutOutTest* cutOuts, SurfaceHit& hit) const {
  FilterContext context;
  rtcInitIntersectContext(&context.base);
  context.cutOuts = cutOuts;
  RTCRayHit rayHit;
  initRay(ray, rayHit.ray);
  rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->top, &context.base, &rayHit);
  if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit.instance = rayHit.hit.instID[0];
  hit.triangle = rayHit.hit.primID;
  hit.u = rayHit.hit.u;
  hit.v = rayHit.hit.v;
  hit.t = rayHit.ray.tfar;
  return true;
}

bool EmbreeScene::occluded(const PtRay& ray, const CutOutTest* cutOuts) const {
  FilterContext context;
  rtcInitIntersectContext(&context.base);
  context.cutOuts = cutOuts;
  RTCRay r;
  initRay(ray, r);
  rtcOccluded1(impl_->top, &context.base, &r);
  return r.tfar < 0.0f;  // Embree sets -inf on a hit
}

namespace {
// Rays per rtcIntersect1M / rtcOccluded1M call: their records stay on the
// stack (about 6 KB), and Embree's stream code forms its packets within one
// call.
constexpr size_t kStreamChunk = 64;

// A stream call's context: Embree forms packets of coherent rays (camera
// and label rays) and traces the rest one by one.
void initStreamContext(FilterContext& context, bool coherent, const CutOutTest* cutOuts) {
  rtcInitIntersectContext(&context.base);
  context.base.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  context.cutOuts = cutOuts;
}
}  // namespace

void EmbreeScene::intersectMany(const PtRay* rays, size_t count, bool coherent, const CutOutTest* cutOuts,
                                SurfaceHit* hits, uint8_t* found) const {
  FilterContext context;
  initStreamContext(context, coherent, cutOuts);
  RTCRayHit records[kStreamChunk];
  for (size_t first = 0; first < count; first += kStreamChunk) {
    const size_t n = std::min(kStreamChunk, count - first);
    for (size_t i = 0; i < n; ++i) {
      initRay(rays[first + i], records[i].ray);
      records[i].hit.geomID = RTC_INVALID_GEOMETRY_ID;
      records[i].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect1M(impl_->top, &context.base, records, unsigned(n), sizeof(RTCRayHit));
    for (size_t i = 0; i < n; ++i) {
      const RTCRayHit& r = records[i];
      found[first + i] = r.hit.geomID != RTC_INVALID_GEOMETRY_ID;
      if (found[first + i]) hits[first + i] = SurfaceHit{r.hit.instID[0], r.hit.primID, r.hit.u, r.hit.v, r.ray.tfar};
    }
  }
}

void EmbreeScene::occludedMany(const PtRay* rays, size_t count, bool coherent, const CutOutTest* cutOuts,
                               uint8_t* occluded) const {
  FilterContext context;
  initStreamContext(context, coherent, cutOuts);
  RTCRay records[kStreamChunk];
  for (size_t first = 0; first < count; first += kStreamChunk) {
    const size_t n = std::min(kStreamChunk, count - first);
    for (size_t i = 0; i < n; ++i) initRay(rays[first + i], records[i]);
    rtcOccluded1M(impl_->top, &context.base, records, unsigned(n), sizeof(RTCRay));
    for (size_t i = 0; i < n; ++i) occluded[first + i] = records[i].tfar < 0.0f;
  }
}

SurfaceGeometry EmbreeScene::geometry(const SurfaceHit& hit) const {
  const Instance& in = instances_[hit.instance];
  const Mesh& mesh = *meshes_[in.mesh];
  const MeshData& d = mesh.data;
  const uint32_t i0 = d.indices[3 * size_t(hit.triangle)], i1 = d.indices[3 * size_t(hit.triangle) + 1],
                 i2 = d.indices[3 * size_t(hit.triangle) + 2];
  const float w = 1.0f - hit.u - hit.v;
  SurfaceGeometry g;
  // World-space vertices, then the point from the barycentrics: more
  // precise than origin + t direction, which matters for the next ray's
  // offset.
  const Vec3f p0 = in.linear * d.positions[i0] + in.translation;
  const Vec3f p1 = in.linear * d.positions[i1] + in.translation;
  const Vec3f p2 = in.linear * d.positions[i2] + in.translation;
  g.position = w * p0 + hit.u * p1 + hit.v * p2;
  g.edge1 = p1 - p0;
  g.edge2 = p2 - p0;
  const Vec3f cross = g.edge1.cross(g.edge2);
  const float crossNorm = cross.norm();
  g.geometricNormal = crossNorm > 0.0f ? Vec3f(cross / crossNorm) : Vec3f(0, 0, 1);
  g.shadingNormal = g.geometricNormal;
  if (d.normals.size() == d.positions.size()) {
    const Vec3f n = in.normalMatrix * (w * d.normals[i0] + hit.u * d.normals[i1] + hit.v * d.normals[i2]);
    const float length = n.norm();
    if (length > 0.0f && std::isfinite(length)) g.shadingNormal = n / length;
  }
  if (d.uvs.size() == d.positions.size()) {
    g.uv = w * d.uvs[i0] + hit.u * d.uvs[i1] + hit.v * d.uvs[i2];
    g.uvEdge1 = d.uvs[i1] - d.uvs[i0];
    g.uvEdge2 = d.uvs[i2] - d.uvs[i0];
  } else {
    g.uv = g.uvEdge1 = g.uvEdge2 = Vec2f::Zero();
  }
  if (d.colors.size() == d.positions.size()) g.color = w * d.colors[i0] + hit.u * d.colors[i1] + hit.v * d.colors[i2];
  // The part whose range starts at or before the triangle.
  const auto& starts = mesh.partFirstTriangle;
  const auto above = std::upper_bound(starts.begin(), starts.end(), hit.triangle);
  g.part = above == starts.begin() ? (starts.empty() ? 0 : mesh.partOfRange[0])
                                   : mesh.partOfRange[size_t(above - starts.begin() - 1)];
  return g;
}

}  // namespace sdg
