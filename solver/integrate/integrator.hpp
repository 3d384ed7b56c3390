#pragma once
// One time step: kick-drift-kick (velocity Verlet), symplectic and second
// order. Density and stress, which depend on positions, are advanced at the
// drift with the mid-step velocity v^{n+1/2}, the staggered arrangement of
// leapfrog schemes for elastodynamics (second order for linear elasticity).
#include "solver/diagnostics/divergence.hpp"

namespace gearsph {

struct Simulation;

namespace integrate {
// Prepares neighbour lists and the rates at t = 0 (call once before step()).
void initialise(Simulation& sim);
// Advances by sim.dt: the method's table of passes (step_total_lagrangian.cpp,
// step_updated_lagrangian.cpp) in as few parallel regions as its barriers
// allow. Throws DivergenceError naming the pass that found the divergence.
void step(Simulation& sim);
// The same table with each run of passes between two barriers in a parallel
// region of its own: the reference the one-region step is tested against
// (tests/test_one_region_step.cpp).
void step_by_terms(Simulation& sim);
}  // namespace integrate

}  // namespace gearsph
