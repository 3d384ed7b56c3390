#pragma once
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
}  // namespace physics
}  // namespace gearsph
