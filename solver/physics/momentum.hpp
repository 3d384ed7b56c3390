#pragma once
// Momentum equation of the updated-Lagrangian method (the seed paper's eq.;
// Monaghan 1992 eq. 2.12, Gray, Monaghan & Swift 2001 eq. 8):
//   dv_i/dt = sum_j m_j (sigma_i/rho_i^2 B_i + sigma_j/rho_j^2 B_j
//                        - Pi_ij I + (R_i + R_j) f_ij^n) . grad_i W_ij
// Pairwise antisymmetric, so linear momentum is conserved to round-off;
// B = I unless the kernel-gradient correction is on. Hourglass damping is
// added here too (see hourglass.hpp). Fills ax, ay.
#include <cstddef>

namespace gearsph {
struct Simulation;
namespace physics {
// Particles lo .. hi (a pass of the step's table): returns the power they
// lose to viscosity and hourglass damping [W/m].
double momentum(Simulation& sim, std::size_t lo, std::size_t hi);
// Every particle, and the energy over dt into the ledger.
void momentum(Simulation& sim, double dt);
}  // namespace physics
}  // namespace gearsph
