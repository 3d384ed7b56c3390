#include "solver/physics/velocity_gradient.hpp"

#include <cmath>

#include "solver/core/passes.hpp"
#include "solver/physics/continuity.hpp"
#include "solver/physics/kernel_correction.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph::physics {

namespace {

// L <- L (I - a L)^{-1}, a = dt/2.
inline void to_mid_step(double& lxx, double& lxy, double& lyx, double& lyy, double a) {
  const double mxx = 1.0 - a * lxx, mxy = -a * lxy, myx = -a * lyx, myy = 1.0 - a * lyy;
  const double inv = 1.0 / (mxx * myy - mxy * myx);
  const double ixx = myy * inv, ixy = -mxy * inv, iyx = -myx * inv, iyy = mxx * inv;
  const double rxx = lxx * ixx + lxy * iyx, rxy = lxx * ixy + lxy * iyy;
  const double ryx = lyx * ixx + lyy * iyx, ryy = lyx * ixy + lyy * iyy;
  lxx = rxx;
  lxy = rxy;
  lyx = ryx;
  lyy = ryy;
}

void store_correction(Particles& p, std::size_t i, const Correction& c) {
  p.bxx[i] = c.lxx;
  p.bxy[i] = c.lxy;
  p.byx[i] = c.lyx;
  p.byy[i] = c.lyy;
  p.bqx0[i] = c.qx[0];
  p.bqx1[i] = c.qx[1];
  p.bqx2[i] = c.qx[2];
  p.bqy0[i] = c.qy[0];
  p.bqy1[i] = c.qy[1];
  p.bqy2[i] = c.qy[2];
  p.correction_order[i] = static_cast<std::uint8_t>(c.order);
}

template <bool kQuadratic, class K>
void velocity_gradient_loop(Simulation& sim, const K& kernel, double half_dt, std::size_t lo,
                            std::size_t hi) {
  Particles& p = sim.particles;
  NeighbourList& nl = sim.neighbours;
  const GradientCorrection requested = sim.method.correction;
  const bool correct = requested != GradientCorrection::None;
  const bool keep_w = sim.method.artificial_stress.enabled();
  const double h = sim.h();
  for (std::size_t i = lo; i < hi; ++i) {
    const double xi = p.x[i], yi = p.y[i], vxi = p.vx[i], vyi = p.vy[i];
    // R = sum_j V_j (v_j - v_i) (x) (-w phi): linear block (the raw SPH
    // gradient) and quadratic block.
    double lxx = 0, lxy = 0, lyx = 0, lyy = 0;
    double rqx[3] = {0, 0, 0}, rqy[3] = {0, 0, 0};
    Moments m;
    double drho = 0;
    for (std::uint32_t k = nl.rows[i]; k < nl.rows[i + 1]; ++k) {
      const std::uint32_t j = nl.j[k];
      const double dx = xi - p.x[j], dy = yi - p.y[j];
      const double r = std::sqrt(dx * dx + dy * dy);
      const double dw_r = kernel.dW(r) / r;  // = -w_ij; r > 0: particles never coincide
      const double gx = dw_r * dx, gy = dw_r * dy;
      nl.dw_r[k] = dw_r;
      if (keep_w) nl.w[k] = kernel.W(r);
      const double vol_j = p.mass[j] / p.rho[j];
      const double dvx = p.vx[j] - vxi, dvy = p.vy[j] - vyi;
      lxx += vol_j * dvx * gx;
      lxy += vol_j * dvx * gy;
      lyx += vol_j * dvy * gx;
      lyy += vol_j * dvy * gy;
      if (correct) m.add(-vol_j * dw_r, dx, dy, kQuadratic);
      if constexpr (kQuadratic) {
        const double q[3] = {dx * dx, dx * dy, dy * dy};
        for (int c = 0; c < 3; ++c) {
          rqx[c] += vol_j * dvx * dw_r * q[c];
          rqy[c] += vol_j * dvy * dw_r * q[c];
        }
      }
      drho += continuity_pair(p.mass[j], dvx, dvy, gx, gy);
    }
    if (correct) {
      const Correction c = correction_from_moments(m, requested, h);
      store_correction(p, i, c);
      // L = R C^T
      const double cxx =
          lxx * c.lxx + lxy * c.lxy + rqx[0] * c.qx[0] + rqx[1] * c.qx[1] + rqx[2] * c.qx[2];
      const double cxy =
          lxx * c.lyx + lxy * c.lyy + rqx[0] * c.qy[0] + rqx[1] * c.qy[1] + rqx[2] * c.qy[2];
      const double cyx =
          lyx * c.lxx + lyy * c.lxy + rqy[0] * c.qx[0] + rqy[1] * c.qx[1] + rqy[2] * c.qx[2];
      const double cyy =
          lyx * c.lyx + lyy * c.lyy + rqy[0] * c.qy[0] + rqy[1] * c.qy[1] + rqy[2] * c.qy[2];
      lxx = cxx;
      lxy = cxy;
      lyx = cyx;
      lyy = cyy;
    }
    // The velocities are v^{n+1/2} but the positions x^{n+1}: map the
    // gradient back to the mid-step configuration, L_mid = L (I - dt/2 L)^-1
    // (chain rule through x_mid = x - dt/2 v). Without it a rigid rotation
    // shows a spurious dilatation omega^2 dt/2 that builds pressure over a
    // revolution; with it the error is third order (spinning-disk tests).
    const double trace_end = lxx + lyy;
    to_mid_step(lxx, lxy, lyx, lyy, half_dt);
    // Uncorrected: the seed paper's continuity sum plus the same mid-step shift.
    drho = correct ? continuity_corrected(p.rho[i], lxx, lyy)
                   : drho - p.rho[i] * ((lxx + lyy) - trace_end);
    p.lxx[i] = lxx;
    p.lxy[i] = lxy;
    p.lyx[i] = lyx;
    p.lyy[i] = lyy;
    p.drho[i] = drho;
  }
}

}  // namespace

void velocity_gradient(Simulation& sim, double dt, std::size_t lo, std::size_t hi) {
  const bool quadratic = sim.method.correction == GradientCorrection::Quadratic;
  with_kernel(sim.discretization.kernel, sim.h(), [&](const auto& kernel) {
    if (quadratic) {
      velocity_gradient_loop<true>(sim, kernel, 0.5 * dt, lo, hi);
    } else {
      velocity_gradient_loop<false>(sim, kernel, 0.5 * dt, lo, hi);
    }
  });
}

void velocity_gradient(Simulation& sim, double dt) {
  NeighbourList& nl = sim.neighbours;
  // The kernel values the artificial stress reads, sized once (the list's
  // builds keep them sized).
  if (sim.method.artificial_stress.enabled() && nl.w.size() != nl.j.size()) {
    nl.w.assign(nl.j.size(), 0.0);
  }
  over_shares<int>(
      "velocity gradient", sim.particles.n, sim.threads,
      [&](std::size_t lo, std::size_t hi, int&) { velocity_gradient(sim, dt, lo, hi); });
}

}  // namespace gearsph::physics
