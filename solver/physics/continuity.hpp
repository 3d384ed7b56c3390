#pragma once
// Continuity (the seed paper's eq.; Monaghan 1992, eq. 2.11):
//   drho_i/dt = sum_j m_j (v_i - v_j) . grad_i W_ij
// With the kernel-gradient correction on, the same sum is taken with the
// corrected gradients, which for equal neighbour densities is
//   drho_i/dt = -rho_i tr(L_i)
// (the corrected divergence), so density and stress see the same strain rate.
namespace gearsph::physics {

// One pair's contribution; (dvx, dvy) = v_j - v_i, (gx, gy) = grad_i W_ij.
inline double continuity_pair(double m_j, double dvx, double dvy, double gx, double gy) {
  return -m_j * (dvx * gx + dvy * gy);
}

inline double continuity_corrected(double rho_i, double lxx, double lyy) {
  return -rho_i * (lxx + lyy);
}

}  // namespace gearsph::physics
