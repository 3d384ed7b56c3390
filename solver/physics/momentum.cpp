#include "solver/physics/momentum.hpp"

#include <cmath>

#include "solver/core/passes.hpp"
#include "solver/physics/artificial_stress.hpp"
#include "solver/physics/artificial_viscosity.hpp"
#include "solver/physics/hourglass.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph::physics {

namespace {

template <bool kQuadratic, bool kArtificialStress, bool kHourglass>
double momentum_loop(Simulation& sim, double inv_w_dx, std::size_t lo, std::size_t hi) {
  Particles& p = sim.particles;
  const NeighbourList& nl = sim.neighbours;
  const ArtificialViscosity& av = sim.method.viscosity;
  const int as_n = sim.method.artificial_stress.n;
  const double hg = sim.method.hourglass.coefficient;
  const double h = sim.h();
  const double eta2 = (av.eta_over_h * h) * (av.eta_over_h * h);
  double dissipated = 0.0;
  for (std::size_t i = lo; i < hi; ++i) {
    const double xi = p.x[i], yi = p.y[i], vxi = p.vx[i], vyi = p.vy[i];
    const double qxx = p.qxx[i], qxy = p.qxy[i], qyx = p.qyx[i], qyy = p.qyy[i];
    const double qqx0 = p.qqx0[i], qqx1 = p.qqx1[i], qqx2 = p.qqx2[i];
    const double qqy0 = p.qqy0[i], qqy1 = p.qqy1[i], qqy2 = p.qqy2[i];
    const double ci = p.cs[i], rhoi = p.rho[i], mi = p.mass[i];
    double ax = 0, ay = 0, power = 0;
    for (std::uint32_t k = nl.rows[i]; k < nl.rows[i + 1]; ++k) {
      const std::uint32_t j = nl.j[k];
      const double dx = xi - p.x[j], dy = yi - p.y[j];
      const double dw_r = nl.dw_r[k];  // W'(r)/r = -w_ij
      const double gx = dw_r * dx, gy = dw_r * dy;
      // Stress: sigma_i/rho_i^2 G_ij - sigma_j/rho_j^2 G_ji (corrected
      // gradients, kernel_correction.hpp): linear blocks act on grad_i W_ij,
      // quadratic blocks on -w_ij (dx^2, dx dy, dy^2).
      double fx = (qxx + p.qxx[j]) * gx + (qxy + p.qxy[j]) * gy;
      double fy = (qyx + p.qyx[j]) * gx + (qyy + p.qyy[j]) * gy;
      const double r2 = dx * dx + dy * dy;
      if constexpr (kQuadratic) {
        const double q0 = dw_r * dx * dx, q1 = dw_r * dx * dy, q2 = dw_r * dy * dy;
        fx += (qqx0 - p.qqx0[j]) * q0 + (qqx1 - p.qqx1[j]) * q1 + (qqx2 - p.qqx2[j]) * q2;
        fy += (qqy0 - p.qqy0[j]) * q0 + (qqy1 - p.qqy1[j]) * q1 + (qqy2 - p.qqy2[j]) * q2;
      }
      // Viscosity: - Pi_ij grad_i W_ij
      const double dvx = vxi - p.vx[j], dvy = vyi - p.vy[j];  // v_ij
      const double vr = dvx * dx + dvy * dy;
      const double pi_ij =
          monaghan_pi(av, h, vr, r2, 0.5 * (ci + p.cs[j]), 0.5 * (rhoi + p.rho[j]));
      fx -= pi_ij * gx;
      fy -= pi_ij * gy;
      const double mj = p.mass[j];
      power += mj * pi_ij * (dvx * gx + dvy * gy);  // >= 0: energy removed
      if constexpr (kArtificialStress) {
        const double fn = artificial_stress_factor(nl.w[k], inv_w_dx, as_n);
        fx += fn * ((p.rxx[i] + p.rxx[j]) * gx + (p.rxy[i] + p.rxy[j]) * gy);
        fy += fn * ((p.rxy[i] + p.rxy[j]) * gx + (p.ryy[i] + p.ryy[j]) * gy);
      }
      ax += mj * fx;
      ay += mj * fy;
      if constexpr (kHourglass) {
        const double inv_r = 1.0 / std::sqrt(r2);
        const double lxx = 0.5 * (p.lxx[i] + p.lxx[j]), lxy = 0.5 * (p.lxy[i] + p.lxy[j]);
        const double lyx = 0.5 * (p.lyx[i] + p.lyx[j]), lyy = 0.5 * (p.lyy[i] + p.lyy[j]);
        const double zeta = nonaffine_rate(dvx, dvy, lxx, lxy, lyx, lyy, dx, dy, inv_r);
        const double w = -gx * dx - gy * dy;  // = -r dW/dr >= 0, a smooth pair weight
        const double f =
            hourglass_damping(hg, rhoi, p.rho[j], ci, p.cs[j], h, w, r2, eta2, zeta, inv_r);
        ax += mj * f * dx;
        ay += mj * f * dy;
        power -= mj * f * (dvx * dx + dvy * dy);
      }
    }
    p.ax[i] = ax;
    p.ay[i] = ay;
    dissipated += 0.5 * mi * power;  // each pair is visited from both ends
  }
  return dissipated;
}

}  // namespace

double momentum(Simulation& sim, std::size_t lo, std::size_t hi) {
  const bool quad = sim.method.correction == GradientCorrection::Quadratic;
  const bool as = sim.method.artificial_stress.enabled();
  const bool hg = sim.method.hourglass.enabled();
  double inv_w_dx = 0.0;
  if (as) {
    with_kernel(sim.discretization.kernel, sim.h(),
                [&](const auto& kernel) { inv_w_dx = 1.0 / kernel.W(sim.discretization.dx); });
  }
  // One instantiation per combination of optional terms: no branches in the
  // pair loop for terms that are off.
  using Loop = double (*)(Simulation&, double, std::size_t, std::size_t);
  static constexpr Loop loops[8] = {
      momentum_loop<false, false, false>, momentum_loop<false, false, true>,
      momentum_loop<false, true, false>,  momentum_loop<false, true, true>,
      momentum_loop<true, false, false>,  momentum_loop<true, false, true>,
      momentum_loop<true, true, false>,   momentum_loop<true, true, true>};
  return loops[(quad ? 4 : 0) + (as ? 2 : 0) + (hg ? 1 : 0)](sim, inv_w_dx, lo, hi);
}

void momentum(Simulation& sim, double dt) {
  const double dissipated = over_shares<double>(
      "momentum", sim.particles.n, sim.threads,
      [&](std::size_t lo, std::size_t hi, double& s) { s += momentum(sim, lo, hi); });
  sim.energy.dissipated += dt * dissipated;
}

}  // namespace gearsph::physics
