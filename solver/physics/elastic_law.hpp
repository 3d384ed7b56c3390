#pragma once
// The elastic laws, plane strain, each once: the solver's stress and the
// diagnostics' stored energy call the same functions.
//
// Total Lagrangian: Saint Venant-Kirchhoff (Bonet & Wood, Nonlinear
// Continuum Mechanics for FE Analysis, 2nd ed., eqs. 6.30 and 6.28),
//   E = (F^T F - I) / 2,   S = lambda tr(E) I + 2 mu E,
//   W = lambda/2 tr(E)^2 + mu E:E   per reference volume,
// with E_zz = 0 (plane strain): S_zz = lambda tr(E).
//
// Updated Lagrangian (the seed paper's hypoelastic update, stress_rate.hpp):
// the energy stored in a linear elastic particle, p^2 / (2K) + S:S / (4G)
// per current volume.
//
// Inline and branch-free: they sit inside the vectorised particle loops.

namespace gearsph::physics {

// Green-Lagrange strain E of a plane deformation gradient F.
struct GreenLagrange {
  double xx, yy, xy;
};
inline GreenLagrange green_lagrange(double fxx, double fxy, double fyx, double fyy) {
  return {0.5 * (fxx * fxx + fyx * fyx - 1.0), 0.5 * (fxy * fxy + fyy * fyy - 1.0),
          0.5 * (fxx * fxy + fyx * fyy)};
}

// The second Piola-Kirchhoff stress of Saint Venant-Kirchhoff.
struct SecondPiola {
  double xx, yy, xy, zz;
};
inline SecondPiola saint_venant_kirchhoff(const GreenLagrange& e, double lambda, double mu) {
  const double tr = e.xx + e.yy;
  return {lambda * tr + 2 * mu * e.xx, lambda * tr + 2 * mu * e.yy, 2 * mu * e.xy, lambda * tr};
}

// Its stored energy per reference volume.
inline double saint_venant_kirchhoff_energy(const GreenLagrange& e, double lambda, double mu) {
  const double tr = e.xx + e.yy;
  return 0.5 * lambda * tr * tr + mu * (e.xx * e.xx + e.yy * e.yy + 2 * e.xy * e.xy);
}

// Updated Lagrangian: the equation of state of the hypoelastic solid, the
// pressure of a linear elastic volume change, p = K (rho / rho0 - 1)
// (Gray, Monaghan & Swift 2001, eq. 2.3, with the bulk modulus K as the
// stiffness; the deviatoric stress follows the Jaumann rate, stress_rate.hpp).
inline double pressure_from_density(double bulk_modulus, double rho, double rho0) {
  return bulk_modulus * (rho / rho0 - 1.0);
}

// Linear elastic energy per current volume from the pressure p and the
// deviatoric stress S (S_zz included), with 1/(2K) and 1/(4G) given.
inline double linear_elastic_energy(double p, double sxx, double syy, double szz, double sxy,
                                    double inv_2k, double inv_4g) {
  const double ss = sxx * sxx + syy * syy + szz * szz + 2.0 * sxy * sxy;
  return p * p * inv_2k + ss * inv_4g;
}

}  // namespace gearsph::physics
