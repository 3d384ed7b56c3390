#include "solver/physics/kernel_correction.hpp"

#include <algorithm>
#include <cmath>

namespace gearsph {

namespace physics {

namespace {

// Smallest-to-largest Cholesky pivot ratio below which a quadratic fit is
// not trusted (in units of h; see tests/test_kernel_correction.cpp for the
// values on lattice interiors, surfaces and corners).
constexpr double kMinRcond = 1e-4;

bool linear_fit(const Moments& m, Correction& c) {
  const double axx = m.a[Moments::index(0, 0)], axy = m.a[Moments::index(0, 1)];
  const double ayy = m.a[Moments::index(1, 1)];
  const double det = axx * ayy - axy * axy;
  const double norm2 = axx * axx + 2 * axy * axy + ayy * ayy;
  // |det| / |A|^2 is 0.5 for a multiple of the identity; 0.05 is a condition
  // number of about 20.
  if (!(det > 0.05 * norm2)) return false;
  const double inv = 1.0 / det;
  c.lxx = ayy * inv;
  c.lxy = -axy * inv;
  c.lyx = -axy * inv;
  c.lyy = axx * inv;
  c.order = GradientCorrection::Linear;
  return true;
}

// Cholesky factorisation A = L L^T of a symmetric 5x5 matrix in place (lower
// triangle). Returns the ratio of the smallest to the largest pivot squared,
// a cheap reciprocal-condition estimate, or 0 if A is not positive definite.
double cholesky5(double a[5][5]) {
  double d_min = 1e300, d_max = 0.0;
  for (int k = 0; k < 5; ++k) {
    double d = a[k][k];
    for (int m = 0; m < k; ++m) d -= a[k][m] * a[k][m];
    if (!(d > 0.0)) return 0.0;
    d_min = std::min(d_min, d);
    d_max = std::max(d_max, d);
    const double l = std::sqrt(d);
    a[k][k] = l;
    for (int r = k + 1; r < 5; ++r) {
      double v = a[r][k];
      for (int m = 0; m < k; ++m) v -= a[r][m] * a[k][m];
      a[r][k] = v / l;
    }
  }
  return d_min / d_max;
}

// Solves L L^T x = e_col with the factor from cholesky5.
void cholesky5_solve_unit(const double l[5][5], int col, double x[5]) {
  double y[5];
  for (int r = 0; r < 5; ++r) {
    double v = r == col ? 1.0 : 0.0;
    for (int m = 0; m < r; ++m) v -= l[r][m] * y[m];
    y[r] = v / l[r][r];
  }
  for (int r = 4; r >= 0; --r) {
    double v = y[r];
    for (int m = r + 1; m < 5; ++m) v -= l[m][r] * x[m];
    x[r] = v / l[r][r];
  }
}

bool quadratic_fit(const Moments& m, double h, Correction& c) {
  // Scale to units of h: phi -> S phi with S = diag(1/h, 1/h, 1/h^2, ...),
  // so the conditioning test does not depend on the unit of length.
  const double s[5] = {1 / h, 1 / h, 1 / (h * h), 1 / (h * h), 1 / (h * h)};
  double a[5][5];
  for (int r = 0; r < 5; ++r) {
    for (int col = 0; col < 5; ++col) a[r][col] = m.a[Moments::index(r, col)] * s[r] * s[col];
  }
  if (!(cholesky5(a) > kMinRcond)) return false;
  // Rows 0-1 of A^{-1} = S (S A S)^{-1} S; (S A S)^{-1} is symmetric, so its
  // rows 0-1 are the solutions for unit vectors e_0, e_1.
  double row0[5], row1[5];
  cholesky5_solve_unit(a, 0, row0);
  cholesky5_solve_unit(a, 1, row1);
  c.lxx = row0[0] * s[0] * s[0];
  c.lxy = row0[1] * s[0] * s[1];
  c.lyx = row1[0] * s[1] * s[0];
  c.lyy = row1[1] * s[1] * s[1];
  for (int k = 0; k < 3; ++k) {
    c.qx[k] = row0[2 + k] * s[0] * s[2 + k];
    c.qy[k] = row1[2 + k] * s[1] * s[2 + k];
  }
  c.order = GradientCorrection::Quadratic;
  return true;
}

}  // namespace

Correction correction_from_moments(const Moments& m, GradientCorrection requested, double h) {
  Correction c;
  if (requested == GradientCorrection::Quadratic && quadratic_fit(m, h, c)) return c;
  if (requested != GradientCorrection::None && linear_fit(m, c)) return c;
  return Correction{};
}

}  // namespace physics
}  // namespace gearsph
