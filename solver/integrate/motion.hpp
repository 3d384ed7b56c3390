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
};

// v += dt_half a for integrated components; prescribed velocities elsewhere.
// Before the drift, a driven rotation gets the chord velocity of its exact
// placement over the step; after it, the velocity at the new position, and
// the powers at v^{n+1} are summed in the same pass (zero before the drift).
KickPowers kick(Simulation& sim, double dt_half, bool before_drift);
// x += dt v for integrated particles; driven particles are placed exactly at
// time sim.time + dt (no drift of a rotating hub over a million steps).
// Returns the number of particles outside the domain afterwards.
std::size_t drift(Simulation& sim, double dt);
// Fraction of the applied loads acting at sim.time (linear ramp).
double load_ramp(const Simulation& sim);
}  // namespace integrate
}  // namespace gearsph
