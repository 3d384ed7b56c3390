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

// Non-affine part of the pair approach speed, projected on e = x_ij / r.
inline double nonaffine_rate(double dvx, double dvy, double lxx, double lxy, double lyx, double lyy,
                             double dx, double dy, double inv_r) {
  const double ex = dvx - (lxx * dx + lxy * dy);
  const double ey = dvy - (lyx * dx + lyy * dy);
  return (ex * dx + ey * dy) * inv_r;
}

}  // namespace gearsph::physics
