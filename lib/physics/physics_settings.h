#pragma once
// The scene's `physics:` section as plain data: what the stacking
// simulation needs besides the stage. No ODE types here, so modules that
// only pass settings along do not depend on the physics engine.
#include <cstdint>

namespace sdg {

struct PhysicsSettings {
  double gravity = 9.81;        // m/s^2, along -up; converted with metersPerUnit
  double density = 1000.0;      // kg/m^3 of dynamic assets (PhysX's default)
  uint32_t solverIterations = 20;
  // A stack is settled when no asset moves faster than these (m/s, rad/s).
  double settleLinearSpeed = 0.01;
  double settleAngularSpeed = 0.1;
  // Extra steps allowed after the fixed schedule to reach those speeds.
  uint32_t maxSettleSteps = 600;
  // An unsettled stack is an error (exit 1) instead of a warning.
  bool requireSettled = false;
};

}  // namespace sdg
