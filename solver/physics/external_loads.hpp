#pragma once
// Accelerations from outside the bodies' own stress: the applied loads
// (Particles::load_ax, load_ay), ramped in linearly over sim.load_ramp_s so
// that a static check starts without a shock; the mass-proportional damping
// a = -c v of quasi-static scenes (c = sim.damping_1_s, `damping`, takes the
// kinetic energy out while the load settles; Rayleigh damping's mass term);
// and the contact accelerations of the step.
#include <cstddef>

namespace gearsph {
struct Simulation;
struct Particles;
namespace physics {
// Fraction of the applied loads acting at sim.time.
double load_ramp(const Simulation& sim);
// ext_a = ramp load_a - damping v (+ contact_a with `contact`) on particles
// lo .. hi. Returns the energy the damping removed over dt.
double external_accelerations(Particles& p, std::size_t lo, std::size_t hi, double ramp,
                              double damping, double dt, bool contact);
}  // namespace physics
}  // namespace gearsph
