#include "solver/diagnostics/stress_recovery.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>
#include <type_traits>

#include "solver/physics/simulation.hpp"

namespace gearsph::diagnostics {

namespace {

// The fit's radius in local spacings: the default kernel's support (3 h, h = dx).
constexpr double kRadiusOverSpacing = 3.0;
// Particles a fit wants, about twice its unknowns (6 quadratic, 3 linear):
// half a disc of three spacings holds about 14 on a body-fitted outline.
constexpr std::size_t kEnoughQuadratic = 12, kEnoughLinear = 8;
constexpr int kMaxGrowths = 6;
// Below this reciprocal condition number of the scaled moment matrix the
// order is lowered (a point with its particles nearly on a line).
constexpr double kMinConditioning = 1e-6;

// Basis of order `order` at d = (X - q) / R: 1, dx, dy[, dx^2, dx dy, dy^2].
int basis(int order, double dx, double dy, double* out) {
  out[0] = 1.0;
  if (order == 0) return 1;
  out[1] = dx;
  out[2] = dy;
  if (order == 1) return 3;
  out[3] = dx * dx;
  out[4] = dx * dy;
  out[5] = dy * dy;
  return 6;
}

}  // namespace

StressRecovery::StressRecovery(const Simulation& sim, int body,
                               const std::vector<geometry::Point>& points, int order,
                               const std::vector<std::uint8_t>* skip) {
  if (body < 0 || body >= static_cast<int>(sim.bodies.size())) {
    throw std::invalid_argument("stress recovery: no such body");
  }
  if (order < 0 || order > 2) throw std::invalid_argument("stress recovery: order 0, 1 or 2");
  const Particles& p = sim.particles;
  const Body& b = sim.bodies[static_cast<std::size_t>(body)];
  fits_.resize(points.size());
  for (std::size_t q = 0; q < points.size(); ++q) {
    const geometry::Point at = points[q];
    // The local spacing: that of the nearest particle.
    std::size_t nearest = b.begin;
    double d2_min = 1e300;
    for (std::size_t i = b.begin; i < b.end; ++i) {
      const double d2 = (p.x0[i] - at.x) * (p.x0[i] - at.x) + (p.y0[i] - at.y) * (p.y0[i] - at.y);
      if (d2 < d2_min) {
        d2_min = d2;
        nearest = i;
      }
    }
    // The radius grows (a quarter at a time) until the fit has enough
    // particles: a point on an outline sees half a disc, and fewer still
    // when a loaded row is skipped.
    Fit& fit = fits_[q];
    std::vector<double> w;
    double R = kRadiusOverSpacing * p.spacing[nearest];
    const std::size_t wanted = order == 2 ? kEnoughQuadratic : kEnoughLinear;
    for (int grow = 0; grow < kMaxGrowths; ++grow, R *= 1.25) {
      fit.particles.clear();
      w.clear();
      for (std::size_t i = b.begin; i < b.end; ++i) {
        if (skip && (*skip)[i]) continue;
        const double dx = p.x0[i] - at.x, dy = p.y0[i] - at.y;
        const double u = (dx * dx + dy * dy) / (R * R);
        if (u >= 1.0) continue;
        // A particle across a crack is not seen from the point (its face is
        // a free surface: geometry/crack.hpp).
        if (geometry::any_crack_cuts(sim.cracks, at, {p.x0[i], p.y0[i]})) continue;
        fit.particles.push_back(i);
        w.push_back((1.0 - u) * (1.0 - u) * (1.0 - u));
      }
      if (fit.particles.size() >= wanted) break;
    }
    // Lower the order until the moment matrix is well conditioned.
    for (int k = order; k >= 0 && !fit.ok; --k) {
      auto solve = [&](auto size) {
        constexpr int m = decltype(size)::value;
        using Vec = Eigen::Matrix<double, m, 1>;
        Eigen::Matrix<double, m, m> M = Eigen::Matrix<double, m, m>::Zero();
        double phi[6] = {};
        for (std::size_t a = 0; a < fit.particles.size(); ++a) {
          const std::size_t i = fit.particles[a];
          basis(k, (p.x0[i] - at.x) / R, (p.y0[i] - at.y) / R, phi);
          const Vec v = Eigen::Map<const Vec>(phi);
          M += w[a] * v * v.transpose();
        }
        const Eigen::LDLT<Eigen::Matrix<double, m, m>> ldlt(M);
        if (fit.particles.size() < static_cast<std::size_t>(m) || ldlt.info() != Eigen::Success ||
            !(ldlt.rcond() > kMinConditioning)) {
          return;
        }
        // The value at q is e0^T M^-1 sum_j w_j phi_j s_j: one weight per particle.
        const Vec row = ldlt.solve(Vec::Unit(0));  // M symmetric: row 0 of M^-1
        fit.weights.resize(fit.particles.size());
        for (std::size_t a = 0; a < fit.particles.size(); ++a) {
          const std::size_t i = fit.particles[a];
          basis(k, (p.x0[i] - at.x) / R, (p.y0[i] - at.y) / R, phi);
          fit.weights[a] = w[a] * row.dot(Eigen::Map<const Vec>(phi));
        }
        fit.ok = true;
      };
      if (k == 2) solve(std::integral_constant<int, 6>{});
      if (k == 1) solve(std::integral_constant<int, 3>{});
      if (k == 0) solve(std::integral_constant<int, 1>{});
    }
  }
}

std::vector<RecoveredStress> StressRecovery::recover(const Simulation& sim) const {
  const Particles& p = sim.particles;
  std::vector<RecoveredStress> out(fits_.size());
  for (std::size_t q = 0; q < fits_.size(); ++q) {
    const Fit& fit = fits_[q];
    RecoveredStress& r = out[q];
    r.neighbours = fit.particles.size();
    r.ok = fit.ok;
    if (!fit.ok) continue;
    for (std::size_t a = 0; a < fit.particles.size(); ++a) {
      const std::size_t i = fit.particles[a];
      const double w = fit.weights[a];
      r.xx += w * p.sigma_xx(i);
      r.yy += w * p.sigma_yy(i);
      r.xy += w * p.sigma_xy(i);
      r.zz += w * p.sigma_zz(i);
      r.ux += w * (p.x[i] - p.x0[i]);
      r.uy += w * (p.y[i] - p.y0[i]);
    }
  }
  return out;
}

}  // namespace gearsph::diagnostics
