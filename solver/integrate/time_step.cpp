#include "solver/integrate/time_step.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "solver/integrate/stability.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph {

double lattice_courant_limit(KernelType kernel, double h_over_dx) {
  // Unit lattice (dx = 1), h = h_over_dx. Scan k over the irreducible part
  // of the Brillouin zone, 0 <= ky <= kx <= pi.
  return with_kernel(kernel, h_over_dx, [&](const auto& k) {
    const int reach = static_cast<int>(std::ceil(k.radius));
    constexpr int kSamples = 96;
    double g_max = 0.0;
    for (int a = 0; a <= kSamples; ++a) {
      const double kx = std::numbers::pi * a / kSamples;
      for (int b = 0; b <= a; ++b) {
        const double ky = std::numbers::pi * b / kSamples;
        double gx = 0.0, gy = 0.0;
        for (int jy = -reach; jy <= reach; ++jy) {
          for (int jx = -reach; jx <= reach; ++jx) {
            const double r = std::sqrt(double(jx * jx + jy * jy));
            if (r == 0.0 || r >= k.radius) continue;
            // grad_i W_ij with x_i - x_j = -(jx, jy)
            const double dw_r = k.dW(r) / r;
            const double s = std::sin(kx * jx + ky * jy);
            gx += s * dw_r * (-jx);
            gy += s * dw_r * (-jy);
          }
        }
        g_max = std::max(g_max, std::hypot(gx, gy));
      }
    }
    return 2.0 / (k.h * g_max);
  });
}

double max_signal_speed(const Simulation& sim) {
  const Particles& p = sim.particles;
  double s = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    s = std::max(s, p.cs[i] + std::hypot(p.vx[i], p.vy[i]));
  }
  return s;
}

// The smallest smoothing length of the scene: graded particles are limited
// by their finest (h_over_dx times the smallest spacing); a lattice's is h.
double finest_h(const Simulation& sim) {
  const Particles& p = sim.particles;
  if (p.n == 0) return sim.h();
  const double s = *std::min_element(p.spacing.begin(), p.spacing.end());
  return s == sim.discretization.dx ? sim.h() : sim.discretization.h_over_dx * s;
}

TimeStepChoice choose_time_step(Simulation& sim, const TimeStepRequest& req) {
  TimeStepChoice c;
  const double h = finest_h(sim);
  c.signal_speed = max_signal_speed(sim);
  const StabilityLimit limit = estimate_stability_limit(sim);
  c.dt_limit = limit.dt_limit;
  c.limited_by =
      limit.damping_rate > 0 ? "elastic operator with artificial viscosity" : "elastic operator";
  // The interior-lattice Courant bound caps it: a scene whose particles are
  // all driven has no free operator to measure, and its stress update still
  // needs the step a wave would.
  const double lattice =
      lattice_courant_limit(sim.discretization.kernel, sim.discretization.h_over_dx) * h /
      c.signal_speed;
  if (lattice < c.dt_limit) {
    c.dt_limit = lattice;
    c.limited_by = "interior-lattice Courant limit";
  }
  if (req.extra_limit_s > 0.0 && req.extra_limit_s < c.dt_limit) {
    c.dt_limit = req.extra_limit_s;
    c.limited_by = req.extra_name;
  }
  c.courant_limit = c.dt_limit * c.signal_speed / h;
  auto refuse = [&](const std::string& what) {
    std::ostringstream msg;
    msg.precision(3);
    msg << what << " is above the stable limit: dt <= " << c.dt_limit
        << " s, Courant number <= " << c.courant_limit << " (set by the " << c.limited_by
        << "; kernel " << kernel_name(sim.discretization.kernel) << ", h = " << h
        << " m, max signal speed " << c.signal_speed << " m/s)";
    throw TimeStepError(msg.str());
  };
  if (req.dt_s) {
    c.dt = *req.dt_s;
    c.chosen_by = "dt_s";
    if (c.dt > c.dt_limit && !req.allow_unstable) {
      std::ostringstream w;
      w.precision(3);
      w << "time step " << c.dt << " s";
      refuse(w.str());
    }
  } else if (req.cfl) {
    c.dt = *req.cfl * h / c.signal_speed;
    c.chosen_by = "cfl";
    if (c.dt > c.dt_limit && !req.allow_unstable) {
      std::ostringstream w;
      w.precision(3);
      w << "Courant number " << *req.cfl << " (dt = " << c.dt << " s)";
      refuse(w.str());
    }
  } else {
    c.dt = kAutoStepFraction * c.dt_limit;
    c.chosen_by = "auto";
  }
  c.courant = c.dt * c.signal_speed / h;
  return c;
}

}  // namespace gearsph
