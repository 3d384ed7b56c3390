#pragma once
// One time step: kick-drift-kick (velocity Verlet), symplectic and second
// order. Density and stress, which depend on positions, are advanced at the
// drift with the mid-step velocity v^{n+1/2}, the staggered arrangement of
// leapfrog schemes for elastodynamics (second order for linear elasticity).
#include <stdexcept>
#include <string>

namespace gearsph {

struct Simulation;

// A run that blew up: which step, which particle, which quantity.
class DivergenceError : public std::runtime_error {
 public:
  DivergenceError(std::string message, long at_step, long at_particle, std::string what,
                  double bad_value)
      : std::runtime_error(std::move(message)),
        step(at_step),
        particle(at_particle),
        quantity(std::move(what)),
        value(bad_value) {}
  long step;
  long particle;
  std::string quantity;
  double value;
};

namespace integrate {
// Prepares neighbour lists and the rates at t = 0 (call once before step()).
void initialise(Simulation& sim);
// Advances by sim.dt. Throws DivergenceError. A total-Lagrangian step
// without torque-driven groups runs its forces, loads, contact and closing
// kick in one parallel region (threads hand over 7 times a step, not 15).
void step(Simulation& sim);
// The same step with each term in a parallel region of its own: the path of
// the other scenes, and the reference the one-region step is tested against
// (tests/test_one_region_step.cpp).
void step_by_terms(Simulation& sim);
}  // namespace integrate

}  // namespace gearsph
