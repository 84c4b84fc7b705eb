#include "render/pathtrace/gpu/gpu_bvh.h"

#include <embree3/rtcore.h>

#include <limits>
#include <string>

#include "core/diagnostics.h"

namespace sdg {
namespace {

// The builder's own tree, in memory Embree's allocator hands out (freed
// with the BVH); flattened into GpuBvhNodes once the build is done.
struct BuildNode {
  bool leaf;
};
struct BuildInner : BuildNode {
  BuildNode* children[4];
  RTCBounds bounds[4];
  unsigned count;
};
struct BuildLeaf : BuildNode {
  unsigned count;
  uint32_t primitives[kGpuMaxLeafSize];
};

void* createInner(RTCThreadLocalAllocator alloc, unsigned childCount, void*) {
  auto* node = static_cast<BuildInner*>(rtcThreadLocalAlloc(alloc, sizeof(BuildInner), 16));
  node->leaf = false;
  node->count = childCount;
  for (auto& c : node->children) c = nullptr;
  return node;
}

void setChildren(void* nodePtr, void** children, unsigned childCount, void*) {
  auto* node = static_cast<BuildInner*>(nodePtr);
  for (unsigned i = 0; i < childCount; ++i) node->children[i] = static_cast<BuildNode*>(children[i]);
  node->count = childCount;
}

void setBounds(void* nodePtr, const RTCBounds** bounds, unsigned childCount, void*) {
  auto* node = static_cast<BuildInner*>(nodePtr);
  for (unsigned i = 0; i < childCount; ++i) node->bounds[i] = *bounds[i];
}

void* createLeaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void*) {
  auto* leaf = static_cast<BuildLeaf*>(rtcThreadLocalAlloc(alloc, sizeof(BuildLeaf), 16));
  leaf->leaf = true;
  leaf->count = unsigned(count);
  for (size_t i = 0; i < count; ++i) leaf->primitives[i] = prims[i].primID;
  return leaf;
}

struct Flattener {
  GpuBvh& out;

  int32_t leafLink(const BuildLeaf& leaf) {
    const uint32_t first = uint32_t(out.order.size());
    for (unsigned i = 0; i < leaf.count; ++i) out.order.push_back(leaf.primitives[i]);
    return gpuLeafLink(first, leaf.count);
  }

  // Depth first, children in the builder's order: the layout depends on the tree alone.
  int32_t inner(const BuildInner& node) {
    const size_t index = out.nodes.size();
    out.nodes.emplace_back();
    int32_t links[4] = {kGpuEmptyChild, kGpuEmptyChild, kGpuEmptyChild, kGpuEmptyChild};
    for (unsigned i = 0; i < node.count; ++i)
      links[i] = node.children[i]->leaf ? leafLink(*static_cast<const BuildLeaf*>(node.children[i]))
                                        : inner(*static_cast<const BuildInner*>(node.children[i]));
    GpuBvhNode& n = out.nodes[index];
    for (unsigned i = 0; i < 4; ++i) {
      const bool used = i < node.count;
      const RTCBounds& b = node.bounds[i];
      n.loX[i] = used ? b.lower_x : 0.0f;
      n.hiX[i] = used ? b.upper_x : 0.0f;
      n.loY[i] = used ? b.lower_y : 0.0f;
      n.hiY[i] = used ? b.upper_y : 0.0f;
      n.loZ[i] = used ? b.lower_z : 0.0f;
      n.hiZ[i] = used ? b.upper_z : 0.0f;
      n.child[i] = links[i];
    }
    return int32_t(index);
  }
};

}  // namespace

GpuBvhBuilder::GpuBvhBuilder() : device_(rtcNewDevice("threads=1,set_affinity=0")) {
  if (!device_) throw RunError("GPU path tracer: cannot create the Embree device for its BVH builder");
}

GpuBvhBuilder::~GpuBvhBuilder() { rtcReleaseDevice(static_cast<RTCDevice>(device_)); }

GpuBvh GpuBvhBuilder::build(const std::vector<Eigen::AlignedBox3f>& boxes, bool highQuality) const {
  RTCDevice device = static_cast<RTCDevice>(device_);
  GpuBvh out;
  std::vector<RTCBuildPrimitive> prims;
  prims.reserve(boxes.size());
  for (size_t i = 0; i < boxes.size(); ++i) {
    const Eigen::AlignedBox3f& b = boxes[i];
    if (b.isEmpty() || !b.min().allFinite() || !b.max().allFinite()) continue;
    prims.push_back(RTCBuildPrimitive{b.min().x(), b.min().y(), b.min().z(), 0, b.max().x(), b.max().y(), b.max().z(),
                                      unsigned(i)});
  }
  if (prims.empty()) {
    out.rootLink = 0;
    GpuBvhNode empty{};
    for (int32_t& c : empty.child) c = kGpuEmptyChild;
    out.nodes.push_back(empty);
    return out;
  }
  RTCBVH bvh = rtcNewBVH(device);
  RTCBuildArguments args = rtcDefaultBuildArguments();
  args.byteSize = sizeof(args);
  args.buildFlags = RTC_BUILD_FLAG_NONE;
  args.buildQuality = highQuality ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM;
  args.maxBranchingFactor = 4;
  args.maxDepth = 48;
  args.sahBlockSize = 1;
  args.minLeafSize = 1;
  args.maxLeafSize = kGpuMaxLeafSize;
  // A triangle test costs the kernel about three node visits' worth (its
  // 48 bytes and a division, against 112 bytes for four boxes), so the SAH
  // is told so: leaves get fewer triangles. On an H100, the Cornell box at
  // 1,024 spp 0.342 -> 0.303 s with 3 against 1 (the demo unchanged);
  // leaves of at most 4 gave 0.333 s, a traversal cost of 2 0.350 s.
  args.traversalCost = 1.0f;
  args.intersectionCost = 3.0f;
  args.bvh = bvh;
  args.primitives = prims.data();
  args.primitiveCount = prims.size();
  args.primitiveArrayCapacity = prims.size();
  args.createNode = createInner;
  args.setNodeChildren = setChildren;
  args.setNodeBounds = setBounds;
  args.createLeaf = createLeaf;
  args.splitPrimitive = nullptr;
  args.buildProgress = nullptr;
  args.userPtr = nullptr;
  void* root = rtcBuildBVH(&args);
  if (!root) {
    rtcReleaseBVH(bvh);
    throw RunError("GPU path tracer: Embree's BVH builder failed (error " +
                   std::to_string(int(rtcGetDeviceError(device))) + ")");
  }
  Flattener flatten{out};
  const auto* node = static_cast<const BuildNode*>(root);
  if (node->leaf) {
    out.rootLink = flatten.leafLink(*static_cast<const BuildLeaf*>(node));
  } else {
    out.rootLink = 0;
    flatten.inner(*static_cast<const BuildInner*>(node));
  }
  rtcReleaseBVH(bvh);
  return out;
}

}  // namespace sdg
