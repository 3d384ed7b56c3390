#include "solver/diagnostics/edge_stress.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

namespace gearsph::diagnostics {

namespace {

using geometry::Point;

// d/ds at s = 0 of the least-squares quadratic through (s_m, v_m).
struct SlopeFit {
  Eigen::Vector3d row;  // the slope is row . (sum_m phi_m v_m), phi = (1, s, s^2)

  explicit SlopeFit(const std::vector<double>& s) {
    Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
    for (double q : s) {
      const Eigen::Vector3d phi(1.0, q, q * q);
      a += phi * phi.transpose();
    }
    // The slope is the second coefficient of a^-1 b.
    row = a.ldlt().solve(Eigen::Vector3d(0.0, 1.0, 0.0));
  }
  double weight(double q) const { return row[0] + row[1] * q + row[2] * q * q; }
};

}  // namespace

std::vector<double> edge_tangential_stress(const EdgeCurve& c, double window, double E, double nu,
                                           const std::vector<double>* normal_stress) {
  const std::size_t n = c.reference.size();
  if (c.displacement.size() != n || c.arc.size() != n ||
      (normal_stress && normal_stress->size() != n)) {
    throw std::invalid_argument("edge stress: one displacement and arc length per point");
  }
  if (n < 3) throw std::invalid_argument("edge stress: a curve needs three points");
  // The closed curve's length, for the arc across its seam.
  const double length = c.closed ? c.arc.back() - c.arc.front() +
                                       geometry::norm(c.reference.front() - c.reference.back())
                                 : 0.0;
  const double e_plane = E / (1.0 - nu * nu);
  std::vector<double> out(n, 0.0);
  std::vector<std::size_t> at;
  std::vector<double> s;
  for (std::size_t k = 0; k < n; ++k) {
    at.assign(1, k);
    s.assign(1, 0.0);
    // Walk both ways along the curve while within the window.
    for (int dir : {-1, 1}) {
      for (std::size_t step = 1; step < n; ++step) {
        const long raw = static_cast<long>(k) + dir * static_cast<long>(step);
        if (!c.closed && (raw < 0 || raw >= static_cast<long>(n))) break;
        const std::size_t m = static_cast<std::size_t>((raw % static_cast<long>(n) + n) % n);
        double ds = c.arc[m] - c.arc[k];
        if (c.closed) {
          if (dir > 0 && ds <= 0.0) ds += length;
          if (dir < 0 && ds >= 0.0) ds -= length;
        }
        if (std::abs(ds) > window || 2 * at.size() > n) break;
        at.push_back(m);
        s.push_back(ds);
      }
    }
    if (at.size() < 3)
      throw std::invalid_argument("edge stress: the window holds under three points");
    const SlopeFit fit(s);
    Point dX{0.0, 0.0}, du{0.0, 0.0};
    for (std::size_t q = 0; q < at.size(); ++q) {
      const double w = fit.weight(s[q]);
      dX = dX + w * c.reference[at[q]];
      du = du + w * c.displacement[at[q]];
    }
    // eps = |dX + du| / |dX| - 1 = (lambda^2 - 1) / (lambda + 1), without
    // the cancellation of a difference of two numbers near one.
    const double xx = geometry::dot(dX, dX);
    const double l2m1 = (2.0 * geometry::dot(dX, du) + geometry::dot(du, du)) / xx;
    const double eps = l2m1 / (std::sqrt(1.0 + l2m1) + 1.0);
    const double snn = normal_stress ? (*normal_stress)[k] : 0.0;
    out[k] = e_plane * eps + nu / (1.0 - nu) * snn;
  }
  return out;
}

}  // namespace gearsph::diagnostics
