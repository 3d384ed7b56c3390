#pragma once
// Kernel-gradient correction, as a weighted least-squares fit.
//
// The SPH gradient sum_j V_j (u_j - u_i) grad_i W_ij is a least-squares fit
// of a linear field with weights w_ij = -W'(r)/r: grad_i W_ij = -w_ij d_ij
// with d_ij = x_i - x_j. Fitting with the same weights over the basis
//   phi(d) = (d_x, d_y, d_x^2, d_x d_y, d_y^2)
// gives corrected gradient weights
//   G_ij = -w_ij C_i phi(d_ij),   C_i = the first two rows of A_i^{-1},
//   A_i = sum_j V_j w_ij phi(d_ij) (x) phi(d_ij)   (5x5, symmetric)
// so that sum_j V_j (u_j - u_i) G_ij is the exact gradient of any field up to
// the order of the basis:
//   none:      C = [I | 0]              plain SPH
//   linear:    C = [A_ll^{-1} | 0]      Bonet & Lok 1999 (exact for linear fields)
//   quadratic: C = rows 0-1 of A^{-1}   exact for quadratic fields
// In a full interior the odd moments vanish and "quadratic" equals "linear";
// at a free surface, where the kernel support is cut, the linear correction
// still leaves an error proportional to the curvature of the field (the
// strain of a bent plate is underestimated in the outer fibres, which makes
// SPH plates too soft), and the quadratic one removes it.
//
// Where A is too ill-conditioned to trust (corners, one-particle-thick
// features) the order is lowered: quadratic -> linear -> none.
#include <cmath>

#include "solver/core/method.hpp"

namespace gearsph {

namespace physics {

// Upper triangle of the symmetric 5x5 moment matrix A, accumulated per pair.
struct Moments {
  double a[15] = {};  // row-major upper triangle: (0,0) (0,1) .. (0,4) (1,1) .. (4,4)
  static constexpr int index(int r, int c) {
    return r <= c ? r * 5 - r * (r - 1) / 2 + (c - r) : index(c, r);
  }
  // Adds V w phi phi^T for one pair (d = x_i - x_j).
  void add(double vw, double dx, double dy, bool quadratic) {
    const double p[5] = {dx, dy, dx * dx, dx * dy, dy * dy};
    const int order = quadratic ? 5 : 2;
    for (int r = 0; r < order; ++r) {
      for (int c = r; c < order; ++c) a[index(r, c)] += vw * p[r] * p[c];
    }
  }
};

// C = [lin | quad]: G_ij = -w_ij (lin d + quad (dx^2, dx dy, dy^2)).
struct Correction {
  double lxx = 1, lxy = 0, lyx = 0, lyy = 1;
  double qx[3] = {0, 0, 0}, qy[3] = {0, 0, 0};
  GradientCorrection order = GradientCorrection::None;
};

// The correction of the requested order, lowered where A is ill-conditioned.
// `h` scales lengths so the conditioning test is independent of units.
Correction correction_from_moments(const Moments& m, GradientCorrection requested, double h);

}  // namespace physics
}  // namespace gearsph
