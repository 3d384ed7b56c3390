#pragma once
// Hourglass (zero-energy mode) control. The SPH gradient does not see a
// zig-zag of period 2 dx, so such modes grow unresisted. Both terms below
// act only on the part of a pair's motion that the particle's own linear
// (affine) field does not explain, so they leave smooth deformation alone.
//
// Total Lagrangian (Ganzenmueller 2015, eq. 20, in the pair-projected form):
//   delta_ij = x_ij - 0.5 (F_i + F_j) X_ij,   force on i
//   f_i = -0.5 c_hg E V_i V_j W0_ij (delta_ij . e_ij) / |X_ij|^2 e_ij
// Updated Lagrangian (the rate analogue: a damping, not a stiffness):
//   dv_ij = v_ij - 0.5 (L_i + L_j) x_ij,   acceleration on i
//   a_i = -c_hg rho_ij c_ij h m_j w_ij (dv_ij . e_ij) / ((|x_ij|^2 + eta^2) rho_i rho_j) e_ij
// with the pair weight w_ij = -r dW/dr (>= 0, same support as W) and
// e_ij the unit vector from j to i. Both are pairwise antisymmetric.
namespace gearsph::physics {

// Total Lagrangian, the pair's stiffness term: with the pair's stretch that
// the mean deformation gradient does not explain, e = x_ij - F_mean X_ij,
// returns -c_hg w0 (e . x_ij) / r^2, where w0 = W0_ij / (2 |X_ij|^2). Times
// E_i V_j / rho0_i (on i) or E_j V_i / rho0_j (on j) and x_ij, it is the
// pair's hourglass acceleration (the stretch per length along the unit pair
// twice: no square root).
inline double hourglass_stiffness(double c_hg, double w0, double dx, double dy, double X, double Y,
                                  double fxx, double fxy, double fyx, double fyy, double r2) {
  const double ex = dx - (fxx * X + fxy * Y), ey = dy - (fyx * X + fyy * Y);
  return -c_hg * w0 * (ex * dx + ey * dy) / r2;
}

// Non-affine part of the pair approach speed, projected on e = x_ij / r.
inline double nonaffine_rate(double dvx, double dvy, double lxx, double lxy, double lyx, double lyy,
                             double dx, double dy, double inv_r) {
  const double ex = dvx - (lxx * dx + lxy * dy);
  const double ey = dvy - (lyx * dx + lyy * dy);
  return (ex * dx + ey * dy) * inv_r;
}

// Updated Lagrangian, the pair's damping term: the acceleration on i per
// m_j along x_ij, for the non-affine approach rate zeta (nonaffine_rate), the
// pair weight w = -r dW/dr and 1/r.
inline double hourglass_damping(double c_hg, double rho_i, double rho_j, double c_i, double c_j,
                                double h, double w, double r2, double eta2, double zeta,
                                double inv_r) {
  const double coef =
      c_hg * 0.5 * (rho_i + rho_j) * 0.5 * (c_i + c_j) * h * w / (r2 + eta2) / (rho_i * rho_j);
  return -coef * zeta * inv_r;
}

}  // namespace gearsph::physics
