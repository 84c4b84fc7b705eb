#include "physics/stack_simulation.h"

#include <algorithm>

namespace sdg {
namespace {

constexpr double kLeftAreaTolerance = 0.01;  // stage units outside the walls at the end
constexpr double kEscapeDistance = 0.5;       // stage units outside the walls during the run

struct LiveAsset {
  size_t surface, index;
  PhysicsWorld::BodyId body;
};

class StackRun {
 public:
  StackRun(const StackPlan& plan, const StackOptions& options) : plan_(plan), options_(options) {
    PhysicsWorld::Config config = options.world;
    Eigen::AlignedBox3d everything;
    for (const StackSurface& s : plan.surfaces)
      for (const WallBox& w : wallBoxes(s)) {
        everything.extend(s.toWorld(w.centre + w.halfExtents));
        everything.extend(s.toWorld(w.centre - w.halfExtents));
      }
    // A body farther than this from every wall has left the world for good.
    double reach = 10.0 + everything.sizes().maxCoeff();
    config.worldBounds = Eigen::AlignedBox3d(everything.min() - Vec3d::Constant(reach),
                                             everything.max() + Vec3d::Constant(reach));
    world_ = std::make_unique<PhysicsWorld>(config);
    for (const StackSurface& s : plan.surfaces)
      for (const WallBox& w : wallBoxes(s)) world_->addStaticBox(w.halfExtents, s.toWorld(w.centre), s.rotation);
    result_.poses.resize(plan.surfaces.size());
    for (size_t s = 0; s < plan.surfaces.size(); ++s) {
      result_.poses[s].resize(plan.assets[s].size());
      for (size_t i = 0; i < plan.assets[s].size(); ++i) result_.poses[s][i] = plan.assets[s][i].drop;
    }
  }

  StackResult run() {
    world_->setFriction(kRunFriction);
    // Falling and shoving need fewer solver iterations than resting: the
    // final phases run with the full count, which is what the poses show.
    world_->setSolverIterations(std::max(1u, options_.world.solverIterations / 2));
    size_t batches = 0;
    for (const auto& a : plan_.assets) batches = std::max(batches, a.size());
    for (size_t k = 0; k < batches; ++k) {
      for (size_t s = 0; s < plan_.surfaces.size(); ++s) {
        if (k >= plan_.assets[s].size()) continue;
        const StackAsset& a = plan_.assets[s][k];
        live_.push_back({s, k, world_->addBody(a.collider, a.drop, a.path + " (" + a.url + ") on " +
                                                                      plan_.surfaces[s].path)});
      }
      simulate(kDropSteps);
    }
    simulate(kSettleSteps);
    const Vec3d directions[] = {Vec3d(0, 1, 0), Vec3d(1, 0, 0), Vec3d(0, -1, 0), Vec3d(-1, 0, 0)};
    for (int round = 0; round < kPushRounds; ++round)
      for (const Vec3d& d : directions) {
        applyForces(d, kPushIntensity);
        simulate(kPushSteps);
      }
    for (int round = 0; round < kPullRounds; ++round) {
      applyForces(Vec3d::Zero(), kPullIntensity);
      simulate(kPullSteps);
    }
    world_->setSolverIterations(options_.world.solverIterations);
    simulate(kFinalSteps);
    world_->setFriction(kFinalFriction);
    // Settle in windows: a window's speeds are net motion over its length,
    // so solver jitter that goes nowhere does not keep a still stack busy.
    uint64_t extra = 0;
    for (;;) {
      std::vector<BodyPose> before = currentPoses();
      int window = int(std::min<uint64_t>(kSettleWindowSteps, options_.maxSettleSteps - extra));
      if (window <= 0) break;
      simulate(window);
      extra += uint64_t(window);
      measureWindow(before, window);
      if (allSettled()) break;
    }
    report(extra);
    return std::move(result_);
  }

 private:
  // Each asset gets the surface's push direction plus its own pull toward
  // the surface origin. (Isaac Sim sums every asset's pull into one shared
  // vector by accident; see the README.) A force lasts one step, and the
  // spec's fixed newtons would fling a light asset through a wall, so the
  // speed one push adds is capped.
  void applyForces(const Vec3d& direction, double intensity) {
    for (const LiveAsset& a : live_) {
      const StackSurface& s = plan_.surfaces[a.surface];
      Vec3d origin = world_->pose(a.body).position;
      Vec3d force = s.rotation * direction * intensity + (s.origin - origin) * intensity * kCentreForceScale;
      const double addedSpeed = force.norm() * options_.world.dt / world_->mass(a.body);
      if (addedSpeed > kMaxPushSpeed) force *= kMaxPushSpeed / addedSpeed;
      world_->addForceAtPoint(a.body, force, origin);
    }
  }

  void simulate(int steps) {
    for (int i = 0; i < steps; ++i) {
      world_->step();
      dropEscapees();
      if (options_.onStep) {
        for (const LiveAsset& a : live_) result_.poses[a.surface][a.index] = world_->pose(a.body);
        options_.onStep(world_->stepCount(), result_.poses);
      }
    }
  }

  // An asset that got past the walls (through a corner, or by tunnelling)
  // has nothing left to land on: it leaves the simulation at once and is
  // reported, instead of falling until it trips the runaway check.
  void dropEscapees() {
    for (size_t i = 0; i < live_.size();) {
      const LiveAsset& a = live_[i];
      const StackAsset& asset = plan_.assets[a.surface][a.index];
      BodyPose pose = world_->pose(a.body);
      if (insideWalls(plan_.surfaces[a.surface], asset, pose, kEscapeDistance)) {
        ++i;
        continue;
      }
      result_.poses[a.surface][a.index] = pose;
      escaped_.push_back({a.surface, asset.path});
      world_->removeBody(a.body);
      live_.erase(live_.begin() + std::ptrdiff_t(i));
    }
  }

  // Indexed by body id.
  std::vector<BodyPose> currentPoses() const {
    std::vector<BodyPose> poses(world_->bodyCount());
    for (const LiveAsset& a : live_) poses[a.body] = world_->pose(a.body);
    return poses;
  }

  // Net speeds of every asset over the window that just ended.
  void measureWindow(const std::vector<BodyPose>& before, int steps) {
    const double seconds = steps * options_.world.dt;
    windowSpeeds_.assign(world_->bodyCount(), {0.0, 0.0});
    for (const LiveAsset& a : live_) {
      BodyPose now = world_->pose(a.body);
      double turned = now.orientation.angularDistance(before[a.body].orientation);
      windowSpeeds_[a.body] = {(now.position - before[a.body].position).norm() / seconds, turned / seconds};
    }
  }

  bool allSettled() const {
    for (const auto& [linear, angular] : windowSpeeds_)
      if (linear > options_.settleLinearSpeed || angular > options_.settleAngularSpeed) return false;
    return true;
  }

  static bool insideWalls(const StackSurface& s, const StackAsset& asset, const BodyPose& pose, double t) {
    Vec3d centre = pose.position + pose.orientation * asset.collider->bounds.center();
    Vec3d local = s.rotation.transpose() * (centre - s.origin) - s.topCentre();
    return std::abs(local.x()) <= s.size.x() / 2 + t && std::abs(local.y()) <= s.size.y() / 2 + t &&
           local.z() >= -t && local.z() <= s.dropHeight + t;
  }

  void report(uint64_t extra) {
    std::vector<ContactDepths> depths = world_->measureContactDepths();
    result_.steps = world_->stepCount();
    result_.reports.resize(plan_.surfaces.size());
    for (size_t s = 0; s < plan_.surfaces.size(); ++s) {
      SurfaceSettleReport& r = result_.reports[s];
      r.surface = plan_.surfaces[s].path;
      r.assets = plan_.assets[s].size();
      r.steps = result_.steps;
      r.extraSettleSteps = extra;
    }
    for (const LiveAsset& a : live_) {
      SurfaceSettleReport& r = result_.reports[a.surface];
      BodyPose pose = world_->pose(a.body);
      result_.poses[a.surface][a.index] = pose;
      // Without a settle window (max_settle_steps 0) the speeds are the instantaneous ones.
      auto [linear, angular] = a.body < windowSpeeds_.size()
                                   ? windowSpeeds_[a.body]
                                   : std::make_pair(world_->linearVelocity(a.body).norm(),
                                                    world_->angularVelocity(a.body).norm());
      r.maxLinearSpeed = std::max(r.maxLinearSpeed, linear);
      r.maxAngularSpeed = std::max(r.maxAngularSpeed, angular);
      r.maxPenetrationSurface = std::max(r.maxPenetrationSurface, depths[a.body].againstStatic);
      r.maxPenetrationAssets = std::max(r.maxPenetrationAssets, depths[a.body].betweenBodies);
      const StackAsset& asset = plan_.assets[a.surface][a.index];
      if (!insideWalls(plan_.surfaces[a.surface], asset, pose, kLeftAreaTolerance)) r.leftArea.push_back(asset.path);
    }
    for (const auto& [surface, path] : escaped_) result_.reports[surface].leftArea.push_back(path);
    for (SurfaceSettleReport& r : result_.reports)
      r.settled = r.maxLinearSpeed <= options_.settleLinearSpeed && r.maxAngularSpeed <= options_.settleAngularSpeed;
  }

  const StackPlan& plan_;
  const StackOptions& options_;
  std::unique_ptr<PhysicsWorld> world_;
  std::vector<LiveAsset> live_;
  std::vector<std::pair<size_t, std::string>> escaped_;  // surface, asset path
  std::vector<std::pair<double, double>> windowSpeeds_;  // net linear, angular speed per live asset
  StackResult result_;
};

}  // namespace

std::vector<WallBox> wallBoxes(const StackSurface& s) {
  const double W = s.size.x(), D = s.size.y(), h = s.dropHeight, t = kWallThickness;
  const Vec3d top = s.topCentre();
  return {
      {"floor", top - Vec3d(0, 0, t / 2), Vec3d(W, D, t) / 2},
      {"ceiling", top + Vec3d(0, 0, h + t / 2), Vec3d(W, D, t) / 2},
      {"left_wall", top + Vec3d(-(W + t) / 2, 0, h / 2), Vec3d(t, D, h) / 2},
      {"right_wall", top + Vec3d((W + t) / 2, 0, h / 2), Vec3d(t, D, h) / 2},
      {"front_wall", top + Vec3d(0, (D + t) / 2, h / 2), Vec3d(W, t, h) / 2},
      {"back_wall", top + Vec3d(0, -(D + t) / 2, h / 2), Vec3d(W, t, h) / 2},
  };
}

StackResult simulateStack(const StackPlan& plan, const StackOptions& options) {
  return StackRun(plan, options).run();
}

}  // namespace sdg
