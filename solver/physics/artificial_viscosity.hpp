#pragma once
// Monaghan artificial viscosity, the seed paper's Pi_ij (Monaghan 1992, eq. 4.1),
// in the three forms the solver uses (below):
//   Pi_ij = (-alpha c_ij phi_ij + beta phi_ij^2) / rho_ij   if v_ij . x_ij < 0
//   phi_ij = h v_ij . x_ij / (|x_ij|^2 + eta^2)
// with pair means c_ij, rho_ij. Pi_ij >= 0, and it enters the momentum
// equation with a minus sign, like a pressure, so it only removes kinetic
// energy (the seed paper's "+ Pi delta" is a sign-convention slip; method.md).
#include <cmath>

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

// The same Pi_ij times the kernel's slope over r, without the neighbour's
// mass, as the total-Lagrangian momentum loop uses it: Pi_ij dW/dr / r with
// Pi = h v.x (beta h v.x - alpha c q) / (q^2 rho), q = r^2 + eta^2, over
// one denominator, so the pair costs one square root and one division.
// Separating pairs (v.x >= 0) are not damped. Symmetric in i and j. GCC
// branches around the division for them. Where more pairs approach, and
// approaching and separating pairs mix at random (the rotating pinion), a
// pair costs more: the division, and the mispredictions; the chunks are
// cut with those pairs weighted (total_lagrangian.cpp, planned_chunks). A
// branch-free form (min(v.x, 0) in the product) made every pair pay the
// division: 10 % more time in that loop on one thread, so the branch stays
// (docs/speed-accuracy.md).
inline double viscosity_pair(double dw0, double h, double vr, double r2, double q, double alpha,
                             double beta, double c_mean, double rho_mean) {
  const double num = dw0 * h * vr * (beta * h * vr - alpha * c_mean * q);
  const double all = num / (q * q * rho_mean * std::sqrt(r2));
  return vr < 0.0 ? all : 0.0;
}

// Its linear part, every pair taken as approaching (the stable-step
// estimate's damping, integrate/stability.cpp): alpha c h / (q rho), which
// multiplies v_ij . x_ij.
inline double monaghan_linear(double alpha, double c_mean, double h, double q, double rho_mean) {
  return alpha * c_mean * h / (q * rho_mean);
}

}  // namespace gearsph::physics
