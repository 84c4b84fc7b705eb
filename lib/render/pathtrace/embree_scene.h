#pragma once
// The path tracer's geometry in Intel Embree 3: one bottom-level BVH per
// distinct mesh, built once, and a top-level scene of instances (one per
// render item) rebuilt each frame, so a moving object costs a new
// transform, not a new BVH.
//
// Embree's headers stay inside embree_scene.cpp (sdg_pathtrace links it
// privately); this interface speaks Eigen.
//
// Determinism: the device runs with "threads=1", so every BVH is built by
// the calling thread alone. Embree documents its builders as deterministic
// for the default build quality, but a closest hit on a shared edge is a
// tie that the BVH's layout breaks; a single-threaded build makes that
// layout, and so every hit, the same on every machine whatever its core
// count. The cost: a large mesh's BVH builds single-threaded, once. (On
// Debian's TBB build, Embree applies the thread limit to every TBB task in
// the process while the device lives; sdgbehave's own threads are
// std::threads, which it does not touch.)
//
// Scenes use Embree's robust mode (no arithmetic shortcuts in traversal and
// triangle tests): a ray through a shared edge is never let through the
// mesh, which would show as light leaks and holes in the labels; it costs
// about 3-8 % of the ray rate.
//
// Cut-outs: a mesh whose instances may have cut-out parts gets a second
// BVH with Embree filter functions that reject a candidate hit where the
// CutOutTest says the surface is clear; other meshes pay nothing for it.
// Closest hits and shadow rays both pass through the clear parts.
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "assets/mesh_data.h"
#include "stage/math_types.h"

namespace sdg {

struct PtRay {
  Vec3f origin;
  Vec3f direction;  // unit
  float tMin = 0.0f;
  float tMax = std::numeric_limits<float>::infinity();
};

struct SurfaceHit {
  uint32_t instance = 0;  // index into the frame's instances
  uint32_t triangle = 0;
  float u = 0, v = 0;     // Embree's barycentrics: p = (1 - u - v) p0 + u p1 + v p2
  float t = 0;
};

// What a hit point is, in world space.
struct SurfaceGeometry {
  Vec3f position;       // from the barycentrics of the world-space triangle
  Vec3f geometricNormal;  // unit, the triangle's winding (not yet faced toward the ray)
  Vec3f shadingNormal;    // unit, the interpolated vertex normal (not yet faced)
  Vec2f uv;               // the mesh's own uvs, interpolated
  Vec3f edge1, edge2;     // world-space p1 - p0, p2 - p0, for tangent frames
  Vec2f uvEdge1, uvEdge2; // their uv differences
  uint32_t part = 0;      // the MeshPart holding the triangle
  Eigen::Vector4f color{1.0f, 1.0f, 1.0f, 1.0f};  // MeshData::colors interpolated; white when the mesh has none
};

// Decides for a candidate hit on a cut-out instance whether the surface is
// there (true) or clear (false). Called from Embree's traversal, on the
// tracing thread; must not throw.
class CutOutTest {
 public:
  virtual ~CutOutTest() = default;
  virtual bool opaqueAt(uint32_t instance, uint32_t triangle, float u, float v) const = 0;
};

struct SceneInstance {
  uint32_t mesh = 0;  // from EmbreeScene::addMesh
  Matrix4d worldFromLocal = Matrix4d::Identity();
  bool cutOut = false;  // some part may be clear: traced through the filtered BVH
};

class EmbreeScene {
 public:
  EmbreeScene();
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Takes a mesh and builds its BVH; returns its index for SceneInstance.
  uint32_t addMesh(MeshData mesh);
  const MeshData& mesh(uint32_t index) const;
  // The frame's instances, replacing the previous frame's; hits name them
  // by their index in `instances`. Instances whose transform is singular,
  // or whose mesh has no triangles, are left out (nothing to hit).
  void setInstances(const std::vector<SceneInstance>& instances);
  // World bounds of the frame's instances (empty when there are none).
  const Eigen::AlignedBox3f& bounds() const { return bounds_; }

  // The closest hit in (tMin, tMax), or false. `cutOuts` may be null when
  // no instance is cut out.
  bool intersect(const PtRay& ray, const CutOutTest* cutOuts, SurfaceHit& hit) const;
  // Whether anything lies in (tMin, tMax).
  bool occluded(const PtRay& ray, const CutOutTest* cutOuts) const;
  // The same for `count` rays at once, through Embree's ray streams
  // (rtcIntersect1M / rtcOccluded1M): found[i] (occluded[i]) is 1 or 0, as
  // the one-ray calls would return. `coherent` tells Embree the rays start
  // close together and point alike (a tile's camera rays), so it traces
  // them as packets; otherwise it traces them one by one without the
  // per-call overhead.
  void intersectMany(const PtRay* rays, size_t count, bool coherent, const CutOutTest* cutOuts, SurfaceHit* hits,
                     uint8_t* found) const;
  void occludedMany(const PtRay* rays, size_t count, bool coherent, const CutOutTest* cutOuts, uint8_t* occluded) const;
  SurfaceGeometry geometry(const SurfaceHit& hit) const;

 private:
  struct Mesh;
  struct Instance;
  void buildFilteredBvh(Mesh& mesh);

  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<std::unique_ptr<Mesh>> meshes_;
  std::vector<Instance> instances_;
  Eigen::AlignedBox3f bounds_;
};

}  // namespace sdg
