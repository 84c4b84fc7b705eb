#pragma once
// UsdSkel: meshes bound to a Skeleton are posed by linear blend skinning at
// the stage's time codes, so that an animated character moves frame to
// frame (docs/usd.md "Skinned meshes").
//
// The math (skelPose, skinPoints) follows UsdSkel's definitions in the
// stage's column-vector convention: a joint's local transform is
// translate * rotate * scale; its skeleton-space transform is its parent's
// times its local one (a joint's parent is the nearest joint path that
// prefixes its own); its skinning transform is skeleton-space times the
// inverse of its bind transform; a point moves by the weighted sum of its
// joints' skinning transforms applied to geomBindTransform * point.
//
// The import step (poseUsdSkinnedMeshes) writes each skinned Mesh's points
// and normals at the stage's start time code and, where the SkelAnimation
// has time samples, the posed points and normals at each of their times
// into the stage's animation table; between two samples the timeline
// interpolates the posed points linearly (not the joints).
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "core/diagnostics.h"
#include "scene_io/usd_losses.h"
#include "stage/math_types.h"
#include "stage/stage.h"
#include "stage/stage_animation.h"
#include "usd/compose.h"

namespace sdg {

struct SkelTopology {
  std::vector<std::string> joints;  // joint paths in the Skeleton's order ("Hip", "Hip/Knee")
  std::vector<int> parent;          // index of each joint's parent; -1 at a root
};

// The parents of `joints`: the nearest joint whose path prefixes each one's.
SkelTopology skelTopology(std::vector<std::string> joints);

// A joint's local transform from its animation's components.
Matrix4d skelLocalTransform(const Vec3d& translation, const Quatd& rotation, const Vec3d& scale);

// Skinning transforms (skeleton space times inverse bind) of every joint
// from their local transforms; `bind` is in skeleton space.
std::vector<Matrix4d> skinningTransforms(const SkelTopology& topology, std::span<const Matrix4d> local,
                                         std::span<const Matrix4d> bind);

// Joint influences of a mesh's points: `perPoint` (joint, weight) pairs per
// point, or one set for the whole mesh when `rigid` (constant interpolation).
// Joint indices are into `skinning` as given to skinPoints.
struct SkinInfluences {
  int perPoint = 0;
  bool rigid = false;
  std::vector<int32_t> joints;
  std::vector<float> weights;
};

// Linear blend skinning of flat xyz `points` (and per-point or per-corner
// flat xyz `normals`, with `cornerPoints` naming each corner's point when
// they are per corner; may be empty) into `outPoints` / `outNormals`, then
// mapped by `after` (skeleton space into the mesh's space). Weights are
// normalised where they do not add up to one; a point with no weight keeps
// geomBind * point.
void skinPoints(std::span<const float> points, std::span<const float> normals, std::span<const int32_t> cornerPoints,
                const Matrix4d& geomBind, const SkinInfluences& influences, std::span<const Matrix4d> skinning,
                const Matrix4d& after, std::vector<float>& outPoints, std::vector<float>& outNormals);

// A USD Mesh with skel:jointIndices as imported: the composed prim and the
// stage prims that hold its geometry (the Mesh, and one per GeomSubset).
struct UsdSkinnedMesh {
  const usd::ComposedPrim* mesh = nullptr;
  std::vector<std::string> stagePaths;
};

// Poses every skinned mesh (see above); a skeleton or binding that cannot
// be read is a located error; blend shapes and dual-quaternion skinning are
// noted as losses (linear blend skinning of the joints is applied).
// `stageOf` maps a composed path to its stage path; `warn` says a thing
// once per key (a mesh that USD itself would not skin).
using UsdSkelWarn = std::function<void(const SourceLoc&, const std::string& key, const std::string& message)>;
void poseUsdSkinnedMeshes(const usd::ComposedStage& composed, const std::vector<UsdSkinnedMesh>& meshes,
                          const std::function<std::string(const std::string&)>& stageOf, const AnimationClock& clock,
                          Stage& stage, UsdLosses& losses, const UsdSkelWarn& warn, Diagnostics& diag);

// Attributes of a Skeleton prim that the skinning consumes (not reported
// as unread where the Skeleton is imported as a group).
bool isSkeletonAttribute(const std::string& name);

}  // namespace sdg
