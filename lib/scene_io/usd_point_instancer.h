#pragma once
// USD's PointInstancer onto the stage. Each instance becomes a copy of its
// prototype's stage subtree under the instancer, named instance_<id>:
// behaviors, physics, the render list and the writers see ordinary prims,
// each instance is its own semantic entity (its prototype's labels, its
// own boxes and instance id), and the copies share the prototype's mesh
// arrays (SharedArray), so the renderer draws them instanced (one draw per
// mesh, render/raster/instance_batches.h).
//
// An instance's transform, as UsdGeomPointInstancer composes it (column
// vectors, most local last): instancer * T(position) * R(orientation) *
// S(scale) * prototype root's own transform. The clone root carries
// xformOp:translate:instance, xformOp:orient:instance and
// xformOp:scale:instance (the last two only when authored) before the
// prototype root's ops; the instancer's transform comes from being its child.
//
// Prototypes beneath the instancer are drawn only as instances: their roots
// are made invisible where they stand (they stay on the stage, so material
// bindings into them hold). Instances whose id is in `invisibleIds` are
// copied and invisible; those in the `inactiveIds` metadata are not copied.
// `velocities` are kept on each instance (instanceVelocity()), and an
// instance with one moves at it on the timeline, as USD extrapolates
// positions from their sample: xformOp:translate:instance is animated
// (stage_animation.h, `clock`: the stage's time codes), so motion vectors
// and flow show it. Copies of a prototype that holds an instancer do not
// move (the animation belongs to the instances first expanded).
#include <cstdint>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "stage/stage.h"
#include "stage/stage_animation.h"
#include "usd/compose.h"

namespace sdg {

// The per-instance arrays of one PointInstancer, as authored (at the
// composed time code), checked against each other.
struct PointInstancerData {
  std::string path;                     // the composed prim
  std::vector<std::string> prototypes;  // composed paths, in relationship order
  std::vector<int32_t> protoIndices;
  std::vector<int64_t> ids;             // empty: the index is the id
  std::vector<Vec3d> positions;
  std::vector<Quatd> orientations;      // empty when not authored; unit length
  std::vector<Vec3d> scales;            // empty when not authored
  std::vector<Vec3d> velocities;        // units per second; empty when not authored
  std::set<int64_t> invisibleIds, inactiveIds;

  size_t size() const { return protoIndices.size(); }
  int64_t idOf(size_t i) const { return ids.empty() ? int64_t(i) : ids[i]; }
  // T(position) * R(orientation) * S(scale): the instance in the instancer's
  // space, before the prototype root's own transform.
  Matrix4d instanceMatrix(size_t i) const;
};

bool isPointInstancer(const usd::ComposedPrim& prim);
// Attributes the instancer consumes (not reported as unmapped).
bool isPointInstancerAttribute(const std::string& name);

// Reads and checks the arrays: lengths equal to protoIndices (or empty where
// optional), indices within the prototypes, finite numbers, non-zero
// quaternions (orientationsf preferred over orientations when both are
// authored, as USD does). Errors located at the attribute; nullopt then.
std::optional<PointInstancerData> readPointInstancer(const usd::ComposedPrim& prim, Diagnostics& diag);

// The velocity (stage units per second, in the instancer's space) a clone
// root carries, or nullopt.
std::optional<Vec3d> instanceVelocity(const Prim& prim);

// Expands the instancers (composed prims, in the order they were imported)
// on `stage`, where the importer defined each and its prototypes; `mapPath`
// maps composed paths to stage paths. Inner instancers (inside another's
// prototype) are expanded first, so outer copies carry their instances.
// `warn(loc, key, message)` reports once per key.
void expandPointInstancers(const std::vector<const usd::ComposedPrim*>& instancers, Stage& stage,
                           const std::function<std::string(const std::string&)>& mapPath,
                           const std::function<void(const SourceLoc&, const std::string&, const std::string&)>& warn,
                           const AnimationClock& clock, Diagnostics& diag);

}  // namespace sdg
