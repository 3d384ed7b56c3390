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
// The opening half of a kick-drift-kick step over particles lo .. hi:
// v^{n+1/2} = v^n + dt/2 a^n for integrated components (a driven rotation
// gets the chord velocity of its exact placement over the step), then
// x^{n+1} = x^n + dt v^{n+1/2}; driven particles are placed exactly at time
// t = t^n + dt (no drift of a rotating hub over a million steps), with the
// angles place_rotations set for t (once per step, before any particle).
void place_rotations(Simulation& sim, double dt);
void kick_drift_particles(Simulation& sim, double dt, double t, std::size_t lo, std::size_t hi);
// Torque-driven groups (torque_driven): each group's moment about its axis
// turns it by half a step, omega += dt_half alpha. It needs every
// particle's acceleration: a pass of its own on one thread, before the
// opening kick and before the closing kick.
void spin_groups(Simulation& sim, double dt_half);
bool torque_driven(const Simulation& sim);
// The closing kick of particles lo .. hi: v^{n+1} = v^{n+1/2} + dt_half
// a^{n+1}; prescribed velocities at the new positions. The powers at v^{n+1}
// are summed in the same pass.
KickPowers closing_kick_particles(Simulation& sim, double dt_half, std::size_t lo, std::size_t hi);
// The power the drive of torque-driven groups supplies along their rotation
// (after the closing spin), added to KickPowers::drive.
double torque_drive_power(const Simulation& sim);
}  // namespace integrate
}  // namespace gearsph
