#include "solver/physics/total_lagrangian.hpp"

#include <cmath>

#include "solver/core/simulation.hpp"
#include "solver/physics/artificial_viscosity.hpp"
#include "solver/physics/kernel_correction.hpp"

namespace gearsph::physics {

void total_lagrangian_setup(Simulation& sim) {
  Particles& p = sim.particles;
  ReferencePairs& rp = sim.reference;
  NeighbourList list;
  const PairSelection sel = PairSelection::SameBody;
  with_kernel(sim.discretization.kernel, sim.h(), [&](const auto& kernel) {
    list.build(p, kernel.radius, sel, /*reference=*/true, sim.threads);
    const std::size_t n = p.n, m = list.entries();
    rp.rows = list.rows;
    rp.j = list.j;
    rp.gix.assign(m, 0.0);
    rp.giy.assign(m, 0.0);
    rp.gjx.assign(m, 0.0);
    rp.gjy.assign(m, 0.0);
    rp.w0.assign(m, 0.0);
    rp.dw0.assign(m, 0.0);
    for (auto* v : {&rp.px, &rp.py, &rp.pyx, &rp.pyy}) v->assign(n, 0.0);
    // Gradient correction of every particle from its reference neighbourhood.
    const GradientCorrection requested = sim.method.correction;
    const bool quadratic = requested == GradientCorrection::Quadratic;
    std::vector<Correction> corr(n);
    for (std::size_t i = 0; i < n; ++i) {
      Moments mom;
      for (std::uint32_t k = rp.rows[i]; k < rp.rows[i + 1]; ++k) {
        const std::uint32_t j = rp.j[k];
        const double dx = p.x0[i] - p.x0[j], dy = p.y0[i] - p.y0[j];
        const double r = std::sqrt(dx * dx + dy * dy);
        rp.w0[k] = kernel.W(r);
        rp.dw0[k] = kernel.dW(r);
        mom.add(-(p.mass[j] / p.rho0[j]) * rp.dw0[k] / r, dx, dy, quadratic);
      }
      if (requested != GradientCorrection::None) {
        corr[i] = correction_from_moments(mom, requested, sim.h());
      }
      p.bxx[i] = corr[i].lxx;
      p.bxy[i] = corr[i].lxy;
      p.byx[i] = corr[i].lyx;
      p.byy[i] = corr[i].lyy;
      p.correction_order[i] = static_cast<std::uint8_t>(corr[i].order);
    }
    // Per entry: G_ij = -w C_i phi(d) and -G_ji = w C_j phi(-d), d = X_i - X_j.
    auto weight = [](const Correction& c, double mw, double dx, double dy, double& gx, double& gy) {
      const double q0 = dx * dx, q1 = dx * dy, q2 = dy * dy;
      gx = mw * (c.lxx * dx + c.lxy * dy + c.qx[0] * q0 + c.qx[1] * q1 + c.qx[2] * q2);
      gy = mw * (c.lyx * dx + c.lyy * dy + c.qy[0] * q0 + c.qy[1] * q1 + c.qy[2] * q2);
    };
    for (std::size_t i = 0; i < n; ++i) {
      for (std::uint32_t k = rp.rows[i]; k < rp.rows[i + 1]; ++k) {
        const std::uint32_t j = rp.j[k];
        const double dx = p.x0[i] - p.x0[j], dy = p.y0[i] - p.y0[j];
        const double r = std::sqrt(dx * dx + dy * dy);
        const double dw_r = rp.dw0[k] / r;  // = -w
        weight(corr[i], dw_r, dx, dy, rp.gix[k], rp.giy[k]);
        double gx = 0, gy = 0;
        weight(corr[j], dw_r, -dx, -dy, gx, gy);  // G_ji
        rp.gjx[k] = -gx;
        rp.gjy[k] = -gy;
      }
    }
  });
}

void total_lagrangian_stress(Simulation& sim) {
  Particles& p = sim.particles;
  ReferencePairs& rp = sim.reference;
  const std::size_t n = p.n;
#pragma omp parallel for num_threads(sim.threads) schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    // F = I + sum_j V0_j (u_j - u_i) (x) g_ij: written with displacements so
    // that round-off does not swamp strains of 1e-6 on positions of 1e-1 m.
    const double uxi = p.x[i] - p.x0[i], uyi = p.y[i] - p.y0[i];
    double fxx = 1, fxy = 0, fyx = 0, fyy = 1;
    for (std::uint32_t k = rp.rows[i]; k < rp.rows[i + 1]; ++k) {
      const std::uint32_t j = rp.j[k];
      const double vol = p.mass[j] / p.rho0[j];
      const double dux = (p.x[j] - p.x0[j]) - uxi, duy = (p.y[j] - p.y0[j]) - uyi;
      fxx += vol * dux * rp.gix[k];
      fxy += vol * dux * rp.giy[k];
      fyx += vol * duy * rp.gix[k];
      fyy += vol * duy * rp.giy[k];
    }
    p.fxx[i] = fxx;
    p.fxy[i] = fxy;
    p.fyx[i] = fyx;
    p.fyy[i] = fyy;
    // Rotation of the polar decomposition F = R U (2D: one angle).
    p.rot[i] = std::atan2(fyx - fxy, fxx + fyy);

    // Saint Venant-Kirchhoff, plane strain (E_zz = 0).
    const Material& mat = sim.material_of(i);
    const double lam = mat.lame_lambda(), mu = mat.shear_modulus();
    const double exx = 0.5 * (fxx * fxx + fyx * fyx - 1.0);
    const double eyy = 0.5 * (fxy * fxy + fyy * fyy - 1.0);
    const double exy = 0.5 * (fxx * fxy + fyx * fyy);
    const double tr = exx + eyy;
    const double sxx = lam * tr + 2 * mu * exx, syy = lam * tr + 2 * mu * eyy, sxy = 2 * mu * exy;
    const double szz = lam * tr;
    // P = F S
    rp.px[i] = fxx * sxx + fxy * sxy;
    rp.py[i] = fxx * sxy + fxy * syy;
    rp.pyx[i] = fyx * sxx + fyy * sxy;
    rp.pyy[i] = fyx * sxy + fyy * syy;
    // Cauchy sigma = F S F^T / J (sigma_zz = S_zz / J) for output.
    const double jac = fxx * fyy - fxy * fyx;
    const double cxx = (rp.px[i] * fxx + rp.py[i] * fxy) / jac;
    const double cyy = (rp.pyx[i] * fyx + rp.pyy[i] * fyy) / jac;
    const double cxy = (rp.px[i] * fyx + rp.py[i] * fyy) / jac;
    const double czz = szz / jac;
    const double mean = (cxx + cyy + czz) / 3.0;
    p.p[i] = -mean;
    p.sxx[i] = cxx - mean;
    p.syy[i] = cyy - mean;
    p.szz[i] = czz - mean;
    p.sxy[i] = cxy;
    p.rho[i] = p.rho0[i] / jac;
  }
}

void total_lagrangian_momentum(Simulation& sim, double dt) {
  Particles& p = sim.particles;
  const ReferencePairs& rp = sim.reference;
  const ArtificialViscosity& av = sim.method.viscosity;
  const double h = sim.h();
  const double hg = sim.method.hourglass.coefficient;
  const std::size_t n = p.n;
  double dissipated = 0.0;
#pragma omp parallel for num_threads(sim.threads) schedule(static) reduction(+ : dissipated)
  for (std::size_t i = 0; i < n; ++i) {
    const double pxx = rp.px[i], pxy = rp.py[i], pyx = rp.pyx[i], pyy = rp.pyy[i];
    const double inv_rho0 = 1.0 / p.rho0[i];
    const double e_mod = sim.material_of(i).E;
    double ax = 0, ay = 0, power = 0;
    for (std::uint32_t k = rp.rows[i]; k < rp.rows[i + 1]; ++k) {
      const std::uint32_t j = rp.j[k];
      const double vol_j = p.mass[j] / p.rho0[j];
      // (P_i B_i + P_j B_j) grad0_i W_ij
      ax += vol_j * inv_rho0 *
            (pxx * rp.gix[k] + pxy * rp.giy[k] + rp.px[j] * rp.gjx[k] + rp.py[j] * rp.gjy[k]);
      ay += vol_j * inv_rho0 *
            (pyx * rp.gix[k] + pyy * rp.giy[k] + rp.pyx[j] * rp.gjx[k] + rp.pyy[j] * rp.gjy[k]);
      // Viscosity on the current pair geometry (reference kernel slope).
      const double dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j];
      const double dvx = p.vx[i] - p.vx[j], dvy = p.vy[i] - p.vy[j];
      const double r2 = dx * dx + dy * dy, inv_r = 1.0 / std::sqrt(r2);
      const double gx = rp.dw0[k] * dx * inv_r, gy = rp.dw0[k] * dy * inv_r;
      const double pi_ij = monaghan_pi(av, h, dvx * dx + dvy * dy, r2, 0.5 * (p.cs[i] + p.cs[j]),
                                       0.5 * (p.rho[i] + p.rho[j]));
      const double mj = p.mass[j];
      ax -= mj * pi_ij * gx;
      ay -= mj * pi_ij * gy;
      power += mj * pi_ij * (dvx * gx + dvy * gy);
      if (hg > 0.0) {
        // Ganzenmueller 2015: penalise x_ij - F_mean X_ij along the pair.
        const double X = p.x0[i] - p.x0[j], Y = p.y0[i] - p.y0[j];
        const double fxx = 0.5 * (p.fxx[i] + p.fxx[j]), fxy = 0.5 * (p.fxy[i] + p.fxy[j]);
        const double fyx = 0.5 * (p.fyx[i] + p.fyx[j]), fyy = 0.5 * (p.fyy[i] + p.fyy[j]);
        const double ex = dx - (fxx * X + fxy * Y), ey = dy - (fyx * X + fyy * Y);
        const double stretch = (ex * dx + ey * dy) * inv_r;
        const double R2 = X * X + Y * Y;
        const double f = -0.5 * hg * e_mod * vol_j * inv_rho0 * rp.w0[k] * stretch / R2 * inv_r;
        ax += f * dx;
        ay += f * dy;
        power -= f * (dvx * dx + dvy * dy);
      }
    }
    p.ax[i] = ax;
    p.ay[i] = ay;
    dissipated += 0.5 * p.mass[i] * power;
  }
  sim.energy.dissipated += dt * dissipated;
}

}  // namespace gearsph::physics
