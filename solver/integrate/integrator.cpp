#include "solver/integrate/integrator.hpp"

#include <cmath>
#include <sstream>

#include "solver/core/simulation.hpp"
#include "solver/diagnostics/guard.hpp"
#include "solver/integrate/motion.hpp"
#include "solver/physics/momentum.hpp"
#include "solver/physics/stress_rate.hpp"
#include "solver/physics/total_lagrangian.hpp"
#include "solver/physics/velocity_gradient.hpp"

namespace gearsph::integrate {

namespace {

// Verlet skin: a tenth of the spacing lasts thousands of steps.
constexpr double kSkinOverDx = 0.1;

bool total_lagrangian(const Simulation& sim) {
  return sim.method.formulation == Formulation::TotalLagrangian;
}

void refresh_neighbours(Simulation& sim) {
  if (total_lagrangian(sim)) return;  // fixed reference pairs
  if (sim.neighbours.entries() > 0 && !sim.neighbours.needs_rebuild(sim.particles)) return;
  const double radius = kernel_support(sim.discretization.kernel) * sim.h();
  sim.neighbours.set_skin(kSkinOverDx * sim.discretization.dx);
  sim.neighbours.build(sim.particles, radius + sim.neighbours.skin(), PairSelection::SameBody,
                       /*reference=*/false, sim.threads);
}

// Rates and accelerations at the current positions; stress advanced by dt.
void forces(Simulation& sim, double dt) {
  if (total_lagrangian(sim)) {
    physics::total_lagrangian_stress(sim);
    physics::total_lagrangian_momentum(sim, dt);
  } else {
    physics::velocity_gradient(sim, dt);
    physics::update_stress(sim, dt);
    physics::momentum(sim, dt);
  }
}

}  // namespace

void initialise(Simulation& sim) {
  if (total_lagrangian(sim)) {
    physics::total_lagrangian_setup(sim);
  } else {
    refresh_neighbours(sim);
  }
  forces(sim, 0.0);  // accelerations at t = 0, stress unchanged
}

void step(Simulation& sim) {
  const double dt = sim.dt;
  kick(sim, 0.5 * dt, true);                   // v^{n+1/2}
  const std::size_t outside = drift(sim, dt);  // x^{n+1}
  sim.time += dt;
  ++sim.step;
  if (outside > 0) diagnostics::throw_divergence(sim);  // names particle + quantity
  refresh_neighbours(sim);                              // Verlet list, skin used up?
  forces(sim, dt);                                      // rho, S at n+1; a^{n+1}
  kick(sim, 0.5 * dt, false);                           // v^{n+1}
  sim.energy.drive_work += dt * drive_power(sim);
}

}  // namespace gearsph::integrate
