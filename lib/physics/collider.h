#pragma once
// The collision shape of a geometry prim, in its local frame. Cube, Sphere
// and Capsule prims map to ODE's exact primitives; every other shape and
// every mesh file gets the convex hull of its vertices, except hulls that
// fill their bounding box (crates, cartons), which become exact boxes: ODE's
// box-box test gives the most stable resting contacts.
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>

#include "assets/mesh_source.h"
#include "physics/convex_hull.h"

namespace sdg {

struct Collider {
  enum class Kind { Box, Sphere, Capsule, Convex };
  Kind kind = Kind::Box;
  Vec3d center = Vec3d::Zero();  // box, sphere, capsule centre in the prim frame
  Vec3d halfExtents = Vec3d::Zero();
  double radius = 0;
  double length = 0;  // capsule, without the caps
  char axis = 'Z';    // capsule
  std::shared_ptr<const ConvexHull> hull;
  double volume = 0;
  Vec3d centroid = Vec3d::Zero();  // centre of mass at uniform density, prim frame
  Eigen::AlignedBox3d bounds;      // of the mesh vertices, prim frame
};

// A hull must fill at least this fraction of its bounding box to become a box.
inline constexpr double kBoxFillFraction = 0.9;

Collider makeCollider(const MeshKey& key, const MeshData& mesh);

// Colliders by mesh key, computed once per process (hulls are the costly
// part, and the same few assets are dropped thousands of times).
class ColliderCache {
 public:
  static ColliderCache& shared();
  // Loads the mesh on first use; RunError for a missing or bad file.
  std::shared_ptr<const Collider> get(const MeshKey& key, const AssetResolver& assets, const std::string& primPath);

 private:
  std::mutex mutex_;
  std::unordered_map<std::string, std::shared_ptr<const Collider>> byKey_;
};

}  // namespace sdg
