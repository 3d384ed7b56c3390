#pragma once
// Monaghan artificial viscosity, the paper's Pi_ij (Monaghan 1992, eq. 4.1):
//   Pi_ij = (-alpha c_ij phi_ij + beta phi_ij^2) / rho_ij   if v_ij . x_ij < 0
//   phi_ij = h v_ij . x_ij / (|x_ij|^2 + eta^2)
// with pair means c_ij, rho_ij. Pi_ij >= 0, and it enters the momentum
// equation with a minus sign, like a pressure, so it only removes kinetic
// energy (the paper's "+ Pi delta" is a sign-convention slip; method.md).
#include "solver/core/method.hpp"

namespace gearsph::physics {

// vr = v_ij . x_ij, r2 = |x_ij|^2.
inline double monaghan_pi(const ArtificialViscosity& av, double h, double vr, double r2,
                          double c_mean, double rho_mean) {
  const double eta = av.eta_over_h * h;
  const double phi = h * vr / (r2 + eta * eta);
  const double pi = (-av.alpha * c_mean * phi + av.beta * phi * phi) / rho_mean;
  // Separating pairs are not damped. Written as a select, but GCC -O3
  // compiles it as a branch around the two divisions (checked in the
  // object code): where approach and separation alternate unpredictably the
  // branch mispredicts, elsewhere it saves the divisions (the
  // total-Lagrangian loop measured both: total_lagrangian.cpp,
  // viscosity_pair). r2 + eta^2 and rho_mean are positive, so the value is
  // always finite.
  return vr < 0.0 ? pi : 0.0;
}

}  // namespace gearsph::physics
