#pragma once
// Monaghan artificial viscosity, the seed paper's Pi_ij (Monaghan 1992, eq. 4.1),
// in the three forms the solver uses (below):
//   Pi_ij = (-alpha c_ij phi_ij + beta phi_ij^2) / rho_ij   if v_ij . x_ij < 0
//   phi_ij = h v_ij . x_ij / (|x_ij|^2 + eta^2)
// with pair means c_ij, rho_ij. Pi_ij >= 0, and it enters the momentum
// equation with a minus sign, like a pressure, so it only removes kinetic
// energy (the seed paper's "+ Pi delta" is a sign-convention slip; method.md).
#include <algorithm>
#include <cmath>

#include "solver/core/method.hpp"

namespace gearsph::physics {

// vr = v_ij . x_ij, r2 = |x_ij|^2.
inline double monaghan_pi(const ArtificialViscosity& av, double h, double vr, double r2,
                          double c_mean, double rho_mean) {
  const double eta = av.eta_over_h * h;
  const double phi = h * vr / (r2 + eta * eta);
  const double pi = (-av.alpha * c_mean * phi + av.beta * phi * phi) / rho_mean;
  // Separating pairs are not damped. r2 + eta^2 and rho_mean are
  // positive, so the value is always finite.
  return vr < 0.0 ? pi : 0.0;
}

// The same Pi_ij times the kernel's slope over r, without the neighbour's
// mass, as the total-Lagrangian momentum loop uses it:
//   Pi_ij dW/dr / r = h v.x (beta h v.x - alpha c q) dW/dr / (q^2 rho r),
//   q = r^2 + eta^2,
// with the distance and density of its denominator taken at the reference
// configuration (|X_ij|, rho0): a distance does not change when the body
// turns, only when it strains, so the two differ by a few times the strain
// (1e-3 in a gear; the kernel's slope is the reference one already). What
// is left is two constants per pair and a polynomial in v.x:
//   Pi_ij dW/dr / r = v (a v - b),  v = min(v_ij . x_ij, 0),
// with no square root, division or branch in the step, and every pair the
// same cost (docs/speed-accuracy-history.md, twelfth round). Separating pairs
// (v.x >= 0) are not damped. The stable-step estimate's damping
// (integrate/stability.cpp) is its linear part, b, exactly.
struct ReferenceViscosity {
  double a = 0.0;  // beta h^2 dW/dr / (q^2 rho0 r)
  double b = 0.0;  // alpha c h dW/dr / (q rho0 r)
};

inline ReferenceViscosity reference_viscosity(const ArtificialViscosity& av, double dw0, double r0,
                                              double h, double c_mean, double rho0_mean) {
  const double q = r0 * r0 + av.eta_over_h * av.eta_over_h * h * h;
  const double common = dw0 * h / (q * q * rho0_mean * r0);
  return {common * av.beta * h, common * av.alpha * c_mean * q};
}

inline double viscosity_pair(double a, double b, double vr) {
  const double v = std::min(vr, 0.0);
  return v * (a * v - b);
}

// Its linear part, every pair taken as approaching (the stable-step
// estimate's damping, integrate/stability.cpp): alpha c h / (q rho), which
// multiplies v_ij . x_ij.
inline double monaghan_linear(double alpha, double c_mean, double h, double q, double rho_mean) {
  return alpha * c_mean * h / (q * rho_mean);
}

}  // namespace gearsph::physics
