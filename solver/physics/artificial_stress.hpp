#pragma once
// Monaghan artificial stress against the tensile instability (Monaghan 2000;
// Gray, Monaghan & Swift 2001, eqs. 18-23). Each particle carries
//   R_i = -epsilon sigma'_i / rho_i^2 for each tensile principal stress
// (zero for compressive ones), rotated back to x-y. A pair then adds
//   m_j (R_i + R_j) f_ij^n . grad_i W_ij,   f_ij = W(r_ij) / W(dx),
// which grows as particles clump and pushes them apart.
#include <cmath>

#include "solver/core/method.hpp"

namespace gearsph::physics {

struct Sym2 {
  double xx, yy, xy;
};

// R_i / nothing else: (sigma_xx, sigma_yy, sigma_xy) in-plane total stress.
inline Sym2 artificial_stress(const ArtificialStress& as, double sxx, double syy, double sxy,
                              double rho) {
  // Principal stresses of the 2x2 in-plane stress.
  const double mean = 0.5 * (sxx + syy);
  const double half_diff = 0.5 * (sxx - syy);
  const double radius = std::sqrt(half_diff * half_diff + sxy * sxy);
  const double s1 = mean + radius, s2 = mean - radius;
  const double scale = -as.epsilon / (rho * rho);
  const double r1 = s1 > 0.0 ? scale * s1 : 0.0;
  const double r2 = s2 > 0.0 ? scale * s2 : 0.0;
  if (r1 == 0.0 && r2 == 0.0) return {0.0, 0.0, 0.0};
  // Principal direction of s1: angle theta with tan(2 theta) = 2 sxy / (sxx - syy).
  const double theta = 0.5 * std::atan2(sxy, half_diff);
  const double cos_t = std::cos(theta), sin_t = std::sin(theta);
  return {r1 * cos_t * cos_t + r2 * sin_t * sin_t, r1 * sin_t * sin_t + r2 * cos_t * cos_t,
          (r1 - r2) * sin_t * cos_t};
}

// f_ij^n with f_ij = W_ij / W(dx).
inline double artificial_stress_factor(double w_ij, double inv_w_dx, int n) {
  const double f = w_ij * inv_w_dx;
  double fn = 1.0;
  for (int k = 0; k < n; ++k) fn *= f;
  return fn;
}

}  // namespace gearsph::physics
