#pragma once
// Applying kinematic constraints (solver/core/motion.hpp) in the integrator.
#include <cstddef>

namespace gearsph {
struct Simulation;
namespace integrate {
// Powers at the velocities a closing kick leaves [W per m of thickness].
struct KickPowers {
  // Delivered by the constraints: sum over constrained components of
  // -m a . v (the reaction the drive supplies to hold the prescribed motion).
  double drive = 0.0;
  // Of the applied loads (load_ax, load_ay) on the particles.
  double load = 0.0;
  KickPowers& operator+=(const KickPowers& o) {
    drive += o.drive;
    load += o.load;
    return *this;
  }
};
#pragma omp declare reduction(+ : KickPowers : omp_out += omp_in) \
    initializer(omp_priv = KickPowers{})

// The opening half of a kick-drift-kick step, in one pass over the
// particles: v^{n+1/2} = v^n + dt/2 a^n for integrated components (a driven
// rotation gets the chord velocity of its exact placement over the step),
// then x^{n+1} = x^n + dt v^{n+1/2}; driven particles are placed exactly at
// time sim.time + dt (no drift of a rotating hub over a million steps).
// Total-Lagrangian runs also get their displacements x^{n+1} - X here.
struct Drift {
  std::size_t outside = 0;         // particles outside the domain afterwards
  std::size_t contacts_moved = 0;  // beyond half the contact list's skin
};
Drift kick_drift(Simulation& sim, double dt);
// kick_drift in parts, for a caller's parallel region (integrator.cpp):
// first, once, the angle of each driven rotation at sim.time + dt (only for
// scenes without torque-driven groups: torque_driven), then the kick and
// drift of particles lo .. hi, adding what it finds to `drift`.
void place_rotations(Simulation& sim, double dt);
void kick_drift_particles(Simulation& sim, double dt, std::size_t lo, std::size_t hi, Drift& drift);
// v^{n+1} = v^{n+1/2} + dt_half a^{n+1}; prescribed velocities at the new
// positions. The powers at v^{n+1} are summed in the same pass.
KickPowers closing_kick(Simulation& sim, double dt_half);
// The closing kick of particles lo .. hi alone, for a caller's parallel
// region; only for scenes without torque-driven groups (whose spin needs
// every particle's acceleration first: torque_driven).
KickPowers closing_kick_particles(Simulation& sim, double dt_half, std::size_t lo, std::size_t hi);
bool torque_driven(const Simulation& sim);
}  // namespace integrate
}  // namespace gearsph
