#pragma once
// One ODE world for one stacking pass: dynamic bodies with colliders from
// prims, static boxes (the walls around a surface), contacts with one
// friction value for the whole world, and fixed-size steps. The world reads
// and writes poses of prim origins; where ODE keeps the centre of mass is
// its own business. Every step checks every body: a non-finite or runaway
// body throws RunError naming it.
#include <memory>
#include <string>
#include <vector>

#include "physics/collider.h"
#include "physics/physics_settings.h"

struct dxGeom;  // ODE's geometry handle, for the collision callback

namespace sdg {

struct BodyPose {
  Vec3d position = Vec3d::Zero();              // the prim origin, world
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

struct ContactDepths {
  double againstStatic = 0;  // deepest body-vs-static contact
  double betweenBodies = 0;  // deepest body-vs-body contact
};

class PhysicsWorld {
 public:
  struct Config {
    double dt = 1.0 / 60.0;
    Vec3d gravity = Vec3d(0, 0, -9.81);  // stage units / s^2
    double density = 1000.0;            // kg per cubic stage unit
    double linearDamping = 0.01;
    double angularDamping = 10.0;
    uint32_t solverIterations = 20;
    double contactLayer = 0.001;        // stage units of allowed overlap
    double maxCorrectingSpeed = 1.0;    // stage units / s
    // A body beyond this box, or faster than maxSpeed, has exploded.
    Eigen::AlignedBox3d worldBounds{Vec3d::Constant(-1e4), Vec3d::Constant(1e4)};
    double maxSpeed = 1e3;
  };
  using BodyId = size_t;

  explicit PhysicsWorld(const Config& config);
  ~PhysicsWorld();
  PhysicsWorld(const PhysicsWorld&) = delete;
  PhysicsWorld& operator=(const PhysicsWorld&) = delete;

  // `name` appears in error messages ("asset X on surface Y").
  BodyId addBody(std::shared_ptr<const Collider> collider, const BodyPose& pose, std::string name);
  void addStaticBox(const Vec3d& halfExtents, const Vec3d& center, const Matrix3d& rotation);
  // QuickStep iterations from the next step on.
  void setSolverIterations(uint32_t iterations);
  // Coulomb friction of every contact from now on.
  void setFriction(double mu) { friction_ = mu; }
  // A force for the next step only, applied at a world point.
  void addForceAtPoint(BodyId body, const Vec3d& force, const Vec3d& point);
  void step();
  // Takes a body out of the simulation (it keeps its last pose).
  void removeBody(BodyId body);

  BodyPose pose(BodyId body) const;
  Vec3d linearVelocity(BodyId body) const;
  Vec3d angularVelocity(BodyId body) const;
  double mass(BodyId body) const;
  size_t bodyCount() const;
  uint64_t stepCount() const { return steps_; }
  // Runs collision detection alone (no step) and reports each body's
  // deepest overlap with static geometry and with other bodies.
  std::vector<ContactDepths> measureContactDepths();

 private:
  struct Impl;
  struct Body;
  static void nearCallback(void* data, ::dxGeom* g1, ::dxGeom* g2);
  void collide(bool createJoints);
  void checkBodies() const;

  std::unique_ptr<Impl> impl_;
  std::vector<Body> bodies_;
  Config config_;
  double friction_ = 0.5;
  uint64_t steps_ = 0;
  std::vector<ContactDepths>* depths_ = nullptr;  // set while measuring
};

}  // namespace sdg
