#pragma once
#include <cstddef>

namespace gearsph {
struct Simulation;
namespace physics {
// First pair loop of an updated-Lagrangian step, at the current positions:
// caches grad_i W_ij (and W_ij) per neighbour entry and computes for every
// particle the velocity gradient L_i = sum_j V_j (v_j - v_i) (x) grad_i W_ij
// (times B_i^T when corrected), the correction B_i and the density rate.
// The velocities are the mid-step ones, so L is mapped to the mid-step
// configuration (dt is the step being taken; 0 at initialisation).
void velocity_gradient(Simulation& sim, double dt);
// The same for particles lo .. hi (a pass of the step's table), once the
// whole-set call above has sized the neighbour list's kernel values.
void velocity_gradient(Simulation& sim, double dt, std::size_t lo, std::size_t hi);
}  // namespace physics
}  // namespace gearsph
