#pragma once
// The volume stack schedule on one ODE world: drop the assets of every
// surface in batches, settle, push toward each surface's centre from four
// sides, pull, finalise; then, with high friction, settle until nothing
// moves faster than the thresholds (or a step cap). Surfaces are walled in
// by six static boxes. Everything the behavior drew at random (how many
// assets, which, where, how turned) comes in the plan; this code adds no
// randomness, so the same plan gives bitwise the same poses.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "physics/physics_world.h"

namespace sdg {

struct StackSurface {
  std::string path;
  Vec3d origin = Vec3d::Zero();               // world position of the surface prim
  Matrix3d rotation = Matrix3d::Identity();   // its world rotation, scale removed
  Vec3d size = Vec3d::Ones();                 // bounds size in its axes, scaled (W, D, H)
  Vec3d mid = Vec3d::Zero();                  // bounds midpoint in its axes, scaled
  double dropHeight = 2.0;                    // also the wall height

  // A point given in the surface's (unscaled) axes, relative to its origin.
  Vec3d toWorld(const Vec3d& local) const { return origin + rotation * local; }
  // The walled volume's centre of the top face, in the surface's axes.
  Vec3d topCentre() const { return mid + Vec3d(0, 0, size.z() / 2); }
};

struct StackAsset {
  std::string path;  // the prim it becomes
  std::string url;
  std::shared_ptr<const Collider> collider;
  BodyPose drop;     // pose of its origin when it is dropped
};

struct StackPlan {
  std::vector<StackSurface> surfaces;
  std::vector<std::vector<StackAsset>> assets;  // per surface, in drop order
};

struct SurfaceSettleReport {
  std::string surface;
  size_t assets = 0;
  uint64_t steps = 0;        // physics steps of the whole pass
  uint64_t extraSettleSteps = 0;
  bool settled = false;
  // Net speeds over the last settle window (kSettleWindowSteps).
  double maxLinearSpeed = 0;   // stage units / s
  double maxAngularSpeed = 0;  // rad / s
  double maxPenetrationSurface = 0;  // deepest asset into the floor or walls
  double maxPenetrationAssets = 0;   // deepest asset into another asset
  std::vector<std::string> leftArea;  // assets found outside the walled volume (removed)
};

struct StackResult {
  std::vector<std::vector<BodyPose>> poses;  // per surface, per asset
  std::vector<SurfaceSettleReport> reports;
  uint64_t steps = 0;
};

struct StackOptions {
  PhysicsWorld::Config world;
  double settleLinearSpeed = 0.01;  // stage units / s
  double settleAngularSpeed = 0.1;
  uint32_t maxSettleSteps = 600;
  // Called after every step with the current poses (renderSimulation).
  std::function<void(uint64_t step, const std::vector<std::vector<BodyPose>>& poses)> onStep;
};

// Schedule constants, shared with the documentation.
inline constexpr int kDropSteps = 10;
inline constexpr int kSettleSteps = 100;
inline constexpr int kPushRounds = 2;
inline constexpr int kPushSteps = 25;
inline constexpr double kPushIntensity = 500;
inline constexpr int kPullRounds = 2;
inline constexpr int kPullSteps = 20;
inline constexpr double kPullIntensity = 250;
inline constexpr double kCentreForceScale = 0.2;
// Most speed one push may add to an asset (stage units / s).
inline constexpr double kMaxPushSpeed = 0.5;
inline constexpr int kFinalSteps = 20;
inline constexpr double kRunFriction = 0.001;
inline constexpr double kFinalFriction = 0.95;
inline constexpr double kWallThickness = 0.4;
// Settling is judged on net motion over windows of this many steps.
inline constexpr int kSettleWindowSteps = 30;

StackResult simulateStack(const StackPlan& plan, const StackOptions& options);

// The six wall boxes of a surface (floor, ceiling, left, right, front,
// back) as centre and half extents in the surface's axes.
struct WallBox {
  const char* name;
  Vec3d centre;
  Vec3d halfExtents;
};
std::vector<WallBox> wallBoxes(const StackSurface& surface);

}  // namespace sdg
