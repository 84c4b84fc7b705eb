#include "physics/collider.h"

#include <algorithm>

#include "core/log.h"

namespace sdg {
namespace {

// Flat or degenerate meshes still need some thickness to rest on.
constexpr double kMinHalfThickness = 0.0005;

Collider boxOf(const Eigen::AlignedBox3d& bounds) {
  Collider c;
  c.kind = Collider::Kind::Box;
  c.center = bounds.center();
  c.halfExtents = (bounds.sizes() / 2).cwiseMax(kMinHalfThickness);
  c.volume = 8 * c.halfExtents.prod();
  c.centroid = c.center;
  return c;
}

}  // namespace

Collider makeCollider(const MeshKey& key, const MeshData& mesh) {
  Eigen::AlignedBox3d bounds;
  for (const Vec3f& p : mesh.positions) bounds.extend(p.cast<double>());
  if (bounds.isEmpty()) bounds.extend(Vec3d::Zero());
  Collider c;
  switch (key.shape) {
    case PrimType::Cube:
      c = boxOf(bounds);
      break;
    case PrimType::Sphere:
      c.kind = Collider::Kind::Sphere;
      c.radius = key.a;
      c.volume = 4.0 / 3.0 * M_PI * key.a * key.a * key.a;
      break;
    case PrimType::Capsule:
      c.kind = Collider::Kind::Capsule;
      c.radius = key.a;
      c.length = key.b;
      c.axis = key.axis;
      c.volume = M_PI * key.a * key.a * (key.b + 4.0 / 3.0 * key.a);
      break;
    default: {
      std::string why;
      std::optional<ConvexHull> hull = computeConvexHull(mesh.positions, &why);
      if (!hull) {
        log::debug("collider for " + key.id() + ": " + why + "; using its bounding box");
        c = boxOf(bounds);
      } else if (hull->volume >= kBoxFillFraction * bounds.volume()) {
        c = boxOf(bounds);
      } else {
        c.kind = Collider::Kind::Convex;
        c.volume = hull->volume;
        c.centroid = hull->centroid;
        c.hull = std::make_shared<const ConvexHull>(std::move(*hull));
      }
    }
  }
  c.bounds = bounds;
  return c;
}

ColliderCache& ColliderCache::shared() {
  static ColliderCache cache;
  return cache;
}

std::shared_ptr<const Collider> ColliderCache::get(const MeshKey& key, const AssetResolver& assets,
                                                   const std::string& primPath) {
  // Files are keyed by where they resolve, so two scenes with different
  // asset roots never share a wrong entry.
  std::string id = key.id();
  if (key.shape == PrimType::Mesh && !key.inlineMesh)
    if (std::optional<std::string> path = assets.resolve(key.asset)) id = "Mesh:" + *path + "#" + key.submesh;
  {
    std::lock_guard lock(mutex_);
    if (auto it = byKey_.find(id); it != byKey_.end()) return it->second;
  }
  auto collider = std::make_shared<const Collider>(makeCollider(key, meshDataFor(key, assets, primPath)));
  std::lock_guard lock(mutex_);
  return byKey_.emplace(id, std::move(collider)).first->second;
}

}  // namespace sdg
