#pragma once
// The process-wide side of ODE: its library initialisation (once, closed at
// exit), its message handlers routed to the project log, and its global
// random seed, which the solver uses to reorder constraints.
namespace sdg::ode {

// Idempotent and thread-safe.
void ensureInitialized();
// Resets ODE's global random seed; call before building each world so the
// same scene steps identically whatever ran before it in the process.
void resetRandomSeed();

}  // namespace sdg::ode
