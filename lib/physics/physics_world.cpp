#include "physics/physics_world.h"

#include <cmath>

#include <ode/ode.h>

#include "core/diagnostics.h"
#include "core/text.h"
#include "physics/ode_runtime.h"

namespace sdg {
namespace {

// Contact softness: a stiff contact (tiny CFM) with a moderate error
// correction, and ODE's friction pyramid scaled by the normal force, which
// keeps stacks standing without the jitter of a fixed friction bound.
constexpr double kContactErp = 0.2;
constexpr double kContactCfm = 1e-5;
constexpr int kMaxContactsPerPair = 4;
constexpr unsigned kStaticCategory = 1u;
constexpr unsigned kDynamicCategory = 2u;

// PhysX damps by v /= (1 + c dt) each step; ODE multiplies by (1 - scale).
double odeDampingScale(double perSecond, double dt) { return perSecond * dt / (1.0 + perSecond * dt); }

std::string formatVec(const Vec3d& v) {
  return "(" + text::formatDouble(v.x()) + ", " + text::formatDouble(v.y()) + ", " + text::formatDouble(v.z()) + ")";
}

}  // namespace

struct PhysicsWorld::Impl {
  dWorldID world = nullptr;
  dSpaceID space = nullptr;         // dynamic bodies
  dSpaceID staticSpace = nullptr;   // walls: few and large, tested against each body's box
  dJointGroupID contacts = nullptr;
  bool createJoints = true;
};

struct PhysicsWorld::Body {
  dBodyID body = nullptr;
  dGeomID geom = nullptr;
  std::shared_ptr<const Collider> collider;
  std::string name;
  bool removed = false;
};

PhysicsWorld::PhysicsWorld(const Config& config) : impl_(std::make_unique<Impl>()), config_(config) {
  ode::ensureInitialized();
  dAllocateODEDataForThread(dAllocateMaskAll);
  ode::resetRandomSeed();
  impl_->world = dWorldCreate();
  impl_->space = dHashSpaceCreate(nullptr);
  impl_->staticSpace = dSimpleSpaceCreate(nullptr);
  impl_->contacts = dJointGroupCreate(0);
  dWorldSetGravity(impl_->world, config.gravity.x(), config.gravity.y(), config.gravity.z());
  dWorldSetERP(impl_->world, 0.2);
  dWorldSetCFM(impl_->world, 1e-9);
  dWorldSetQuickStepNumIterations(impl_->world, int(config.solverIterations));
  dWorldSetContactSurfaceLayer(impl_->world, config.contactLayer);
  dWorldSetContactMaxCorrectingVel(impl_->world, config.maxCorrectingSpeed);
  // Resting bodies sleep; a contact with a moving body or a force wakes them.
  dWorldSetAutoDisableFlag(impl_->world, 1);
  dWorldSetAutoDisableLinearThreshold(impl_->world, 0.02);
  dWorldSetAutoDisableAngularThreshold(impl_->world, 0.05);
  dWorldSetAutoDisableSteps(impl_->world, 5);
  dWorldSetAutoDisableTime(impl_->world, 0);
}

PhysicsWorld::~PhysicsWorld() {
  for (Body& b : bodies_) {
    dGeomDestroy(b.geom);
    dBodyDestroy(b.body);
  }
  dJointGroupDestroy(impl_->contacts);
  dSpaceDestroy(impl_->space);
  dSpaceDestroy(impl_->staticSpace);  // destroys the static geoms it holds
  dWorldDestroy(impl_->world);
}

PhysicsWorld::BodyId PhysicsWorld::addBody(std::shared_ptr<const Collider> collider, const BodyPose& pose,
                                           std::string name) {
  const Collider& c = *collider;
  Body b;
  b.body = dBodyCreate(impl_->world);
  dMass mass;
  const double total = std::max(c.volume, 1e-12) * config_.density;
  switch (c.kind) {
    case Collider::Kind::Box: {
      Vec3d size = 2 * c.halfExtents;
      b.geom = dCreateBox(impl_->space, size.x(), size.y(), size.z());
      dMassSetBoxTotal(&mass, total, size.x(), size.y(), size.z());
      break;
    }
    case Collider::Kind::Sphere:
      b.geom = dCreateSphere(impl_->space, c.radius);
      dMassSetSphereTotal(&mass, total, c.radius);
      break;
    case Collider::Kind::Capsule:
      b.geom = dCreateCapsule(impl_->space, c.radius, c.length);
      dMassSetCapsuleTotal(&mass, total, 3, c.radius, c.length);
      break;
    case Collider::Kind::Convex: {
      const ConvexHull& h = *c.hull;
      // ODE keeps these pointers; the shared collider outlives the geom.
      b.geom = dCreateConvex(impl_->space, const_cast<double*>(h.planes.data()), unsigned(h.faceCount),
                             const_cast<double*>(h.points.data()), unsigned(h.pointCount()),
                             const_cast<unsigned*>(h.polygons.data()));
      // The hull's bounding box stands in for its inertia tensor.
      Vec3d size = c.bounds.sizes().cwiseMax(1e-3);
      dMassSetBoxTotal(&mass, total, size.x(), size.y(), size.z());
      break;
    }
  }
  dBodySetMass(b.body, &mass);
  dGeomSetBody(b.geom, b.body);
  // The body sits at the centre of mass; the shape keeps its place in the prim frame.
  Vec3d shapeOffset = (c.kind == Collider::Kind::Convex ? Vec3d::Zero() : c.center) - c.centroid;
  dGeomSetOffsetPosition(b.geom, shapeOffset.x(), shapeOffset.y(), shapeOffset.z());
  if (c.kind == Collider::Kind::Capsule && c.axis != 'Z') {
    dMatrix3 r;
    if (c.axis == 'X') dRFromAxisAndAngle(r, 0, 1, 0, M_PI / 2);
    else dRFromAxisAndAngle(r, 1, 0, 0, -M_PI / 2);
    dGeomSetOffsetRotation(b.geom, r);
  }
  dGeomSetCategoryBits(b.geom, kDynamicCategory);
  dGeomSetCollideBits(b.geom, kStaticCategory | kDynamicCategory);
  Vec3d com = pose.position + pose.orientation * c.centroid;
  dBodySetPosition(b.body, com.x(), com.y(), com.z());
  const Eigen::Quaterniond& q = pose.orientation;
  dQuaternion odeQ = {q.w(), q.x(), q.y(), q.z()};
  dBodySetQuaternion(b.body, odeQ);
  dBodySetLinearDamping(b.body, odeDampingScale(config_.linearDamping, config_.dt));
  dBodySetAngularDamping(b.body, odeDampingScale(config_.angularDamping, config_.dt));
  dBodySetLinearDampingThreshold(b.body, 0);
  dBodySetAngularDampingThreshold(b.body, 0);
  dBodySetData(b.body, reinterpret_cast<void*>(uintptr_t(bodies_.size())));
  b.collider = std::move(collider);
  b.name = std::move(name);
  bodies_.push_back(std::move(b));
  return bodies_.size() - 1;
}

void PhysicsWorld::addStaticBox(const Vec3d& halfExtents, const Vec3d& center, const Matrix3d& rotation) {
  Vec3d size = 2 * halfExtents;
  dGeomID g = dCreateBox(impl_->staticSpace, size.x(), size.y(), size.z());
  dGeomSetPosition(g, center.x(), center.y(), center.z());
  dMatrix3 r;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r[4 * i + j] = rotation(i, j);
    r[4 * i + 3] = 0;
  }
  dGeomSetRotation(g, r);
  dGeomSetCategoryBits(g, kStaticCategory);
  dGeomSetCollideBits(g, kDynamicCategory);
}

void PhysicsWorld::setSolverIterations(uint32_t iterations) {
  dWorldSetQuickStepNumIterations(impl_->world, int(iterations));
}

void PhysicsWorld::addForceAtPoint(BodyId body, const Vec3d& force, const Vec3d& point) {
  dBodyID b = bodies_.at(body).body;
  dBodyEnable(b);
  dBodyAddForceAtPos(b, force.x(), force.y(), force.z(), point.x(), point.y(), point.z());
}

void PhysicsWorld::nearCallback(void* data, dGeomID g1, dGeomID g2) {
  auto* self = static_cast<PhysicsWorld*>(data);
  dBodyID b1 = dGeomGetBody(g1), b2 = dGeomGetBody(g2);
  if (!b1 && !b2) return;
  // Two sleeping bodies cannot push each other; skip the narrow phase.
  if (self->impl_->createJoints && (!b1 || !dBodyIsEnabled(b1)) && (!b2 || !dBodyIsEnabled(b2))) return;
  dContact contact[kMaxContactsPerPair];
  int n = dCollide(g1, g2, kMaxContactsPerPair, &contact[0].geom, sizeof(dContact));
  if (!self->impl_->createJoints) {
    bool againstStatic = !b1 || !b2;
    for (int i = 0; i < n; ++i)
      for (dBodyID b : {b1, b2}) {
        if (!b) continue;
        ContactDepths& d = (*self->depths_)[reinterpret_cast<uintptr_t>(dBodyGetData(b))];
        double& deepest = againstStatic ? d.againstStatic : d.betweenBodies;
        deepest = std::max(deepest, double(contact[i].geom.depth));
      }
    return;
  }
  for (int i = 0; i < n; ++i) {
    dSurfaceParameters& s = contact[i].surface;
    s.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
    s.mu = self->friction_;
    s.soft_erp = kContactErp;
    s.soft_cfm = kContactCfm;
    dJointID j = dJointCreateContact(self->impl_->world, self->impl_->contacts, &contact[i]);
    dJointAttach(j, b1, b2);
  }
}

void PhysicsWorld::collide(bool createJoints) {
  impl_->createJoints = createJoints;
  dSpaceCollide(impl_->space, this, &PhysicsWorld::nearCallback);
  dSpaceCollide2(reinterpret_cast<dGeomID>(impl_->space), reinterpret_cast<dGeomID>(impl_->staticSpace), this,
                 &PhysicsWorld::nearCallback);
}

void PhysicsWorld::step() {
  collide(true);
  dWorldQuickStep(impl_->world, config_.dt);
  dJointGroupEmpty(impl_->contacts);
  ++steps_;
  checkBodies();
}

void PhysicsWorld::removeBody(BodyId body) {
  Body& b = bodies_.at(body);
  dBodyDisable(b.body);
  dGeomDisable(b.geom);
  b.removed = true;
}

void PhysicsWorld::checkBodies() const {
  for (const Body& b : bodies_) {
    if (b.removed) continue;
    const double* p = dBodyGetPosition(b.body);
    const double* v = dBodyGetLinearVel(b.body);
    Vec3d position(p[0], p[1], p[2]), velocity(v[0], v[1], v[2]);
    const char* what = nullptr;
    if (!position.allFinite() || !velocity.allFinite()) what = "exploded (its position or velocity is not a number)";
    else if (!config_.worldBounds.contains(position)) what = "left the world";
    else if (velocity.norm() > config_.maxSpeed) what = "exploded (it moves faster than the speed limit)";
    if (what)
      throw RunError("physics: " + b.name + " " + what + " at step " + std::to_string(steps_) + ": position " +
                     formatVec(position) + ", velocity " + formatVec(velocity));
  }
}

BodyPose PhysicsWorld::pose(BodyId body) const {
  const Body& b = bodies_.at(body);
  const double* p = dBodyGetPosition(b.body);
  const double* q = dBodyGetQuaternion(b.body);
  BodyPose pose;
  pose.orientation = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
  pose.position = Vec3d(p[0], p[1], p[2]) - pose.orientation * b.collider->centroid;
  return pose;
}

Vec3d PhysicsWorld::linearVelocity(BodyId body) const {
  const double* v = dBodyGetLinearVel(bodies_.at(body).body);
  return Vec3d(v[0], v[1], v[2]);
}

Vec3d PhysicsWorld::angularVelocity(BodyId body) const {
  const double* v = dBodyGetAngularVel(bodies_.at(body).body);
  return Vec3d(v[0], v[1], v[2]);
}

size_t PhysicsWorld::bodyCount() const { return bodies_.size(); }

double PhysicsWorld::mass(BodyId body) const {
  dMass m;
  dBodyGetMass(bodies_.at(body).body, &m);
  return m.mass;
}

std::vector<ContactDepths> PhysicsWorld::measureContactDepths() {
  std::vector<ContactDepths> depths(bodies_.size());
  depths_ = &depths;
  collide(false);
  depths_ = nullptr;
  return depths;
}

}  // namespace sdg
