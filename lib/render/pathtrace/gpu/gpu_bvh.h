#pragma once
// BVHs for the GPU path tracer, built by Embree's BVH builder
// (rtcBuildBVH) into this tracer's own node layout: 4-wide nodes that hold
// their four children's boxes (structure of arrays, one load per axis on
// the GPU) and child links, 112 bytes; leaves are ranges of at most 16
// primitives, reordered so each leaf's are consecutive. The builder runs
// on one thread (an Embree device with threads=1), so a BVH is the same on
// every machine and every run; the GPU traversal then finds the same hits.
#include <cstdint>
#include <vector>

#include "stage/math_types.h"

namespace sdg {

struct GpuBvhNode {  // std430 layout of pt_scene.glsl's Node
  float loX[4], hiX[4], loY[4], hiY[4], loZ[4], hiZ[4];
  int32_t child[4];
};
static_assert(sizeof(GpuBvhNode) == 112, "the shader reads 112-byte nodes");

inline constexpr int32_t kGpuEmptyChild = 0x7fffffff;
inline constexpr int kGpuMaxLeafSize = 8;

// A leaf as a child link: negative, ~(first << 4 | (count - 1)).
inline int32_t gpuLeafLink(uint32_t first, uint32_t count) { return ~int32_t((first << 4) | (count - 1)); }

struct GpuBvh {
  std::vector<GpuBvhNode> nodes;  // nodes[0] is the root unless rootLink is a leaf
  int32_t rootLink = 0;           // 0 (the root node) or a leaf link when everything fits one leaf
  std::vector<uint32_t> order;    // the primitives in leaf order: leaf ranges index this
};

// Owns a single-threaded Embree device while the tracer lives.
class GpuBvhBuilder {
 public:
  GpuBvhBuilder();
  ~GpuBvhBuilder();
  GpuBvhBuilder(const GpuBvhBuilder&) = delete;
  GpuBvhBuilder& operator=(const GpuBvhBuilder&) = delete;

  // A BVH over `boxes` (one per primitive; empty ones are left out).
  // Throws RunError when Embree fails.
  GpuBvh build(const std::vector<Eigen::AlignedBox3f>& boxes, bool highQuality) const;

 private:
  void* device_;  // RTCDevice: Embree's header stays in the .cpp
};

}  // namespace sdg
