#include "solver/physics/total_lagrangian.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

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
    // W itself is needed only by hourglass control: without it an entry
    // takes 8 bytes less (docs/speed-accuracy.md, memory per particle).
    const bool keep_w = sim.method.hourglass.enabled();
    rp.w0.assign(keep_w ? m : 0, 0.0);
    rp.dw0.assign(m, 0.0);
    for (auto* v : {&rp.px, &rp.py, &rp.pyx, &rp.pyy, &rp.ux, &rp.uy}) v->assign(n, 0.0);
    rp.vol0.resize(n);
    for (std::size_t i = 0; i < n; ++i) rp.vol0[i] = p.mass[i] / p.rho0[i];
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
        if (keep_w) rp.w0[k] = kernel.W(r);
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
        const double vol_j = rp.vol0[j];
        double gx = 0, gy = 0;
        weight(corr[i], dw_r, dx, dy, gx, gy);
        rp.gix[k] = vol_j * gx;
        rp.giy[k] = vol_j * gy;
        weight(corr[j], dw_r, -dx, -dy, gx, gy);  // G_ji
        rp.gjx[k] = -vol_j * gx;
        rp.gjy[k] = -vol_j * gy;
      }
    }
    rp.upper.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const auto first = rp.j.begin() + rp.rows[i], last = rp.j.begin() + rp.rows[i + 1];
      rp.upper[i] = static_cast<std::uint32_t>(
          std::upper_bound(first, last, static_cast<std::uint32_t>(i)) - rp.j.begin());
    }
    rp.sgx.assign(n, 0.0);
    rp.sgy.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::uint32_t k = rp.rows[i]; k < rp.rows[i + 1]; ++k) {
        rp.sgx[i] += rp.gix[k];
        rp.sgy[i] += rp.giy[k];
      }
    }
  });
  rp.lambda_body.clear();
  rp.mu_body.clear();
  for (const Body& b : sim.bodies) {
    rp.lambda_body.push_back(b.material.lame_lambda());
    rp.mu_body.push_back(b.material.shear_modulus());
  }
}

void total_lagrangian_stress(Simulation& sim) {
  Particles& p = sim.particles;
  ReferencePairs& rp = sim.reference;
  const std::size_t n = p.n;
  const std::uint32_t* rows = rp.rows.data();
  const std::uint32_t* jj = rp.j.data();
  const double* gix = rp.gix.data();
  const double* giy = rp.giy.data();
  const double* lambda_body = rp.lambda_body.data();
  const double* mu_body = rp.mu_body.data();
  double* ux = rp.ux.data();
  double* uy = rp.uy.data();
  // Contact candidates (penalty contact only), refreshed before this step's forces.
  const std::uint32_t* contact_rows =
      sim.contacts.rows.size() == n + 1 ? sim.contacts.rows.data() : nullptr;
  // One parallel region, two work-shared loops: the displacements first, so
  // that the pair loop reads one array per component instead of two.
#pragma omp parallel num_threads(sim.threads)
  {
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      ux[i] = p.x[i] - p.x0[i];
      uy[i] = p.y[i] - p.y0[i];
    }
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      // F = I + sum_j V0_j (u_j - u_i) (x) g_ij: written with displacements so
      // that round-off does not swamp strains of 1e-6 on positions of 1e-1 m
      // (the sum of the small terms is formed first, then added to I).
      const double uxi = ux[i], uyi = uy[i];
      double sxx_ = 0, sxy_ = 0, syx_ = 0, syy_ = 0;
      for (std::uint32_t k = rows[i]; k < rows[i + 1]; ++k) {
        const std::uint32_t j = jj[k];
        const double dux = ux[j] - uxi, duy = uy[j] - uyi;
        sxx_ += dux * gix[k];
        sxy_ += dux * giy[k];
        syx_ += duy * gix[k];
        syy_ += duy * giy[k];
      }
      const double fxx = 1.0 + sxx_, fxy = sxy_, fyx = syx_, fyy = 1.0 + syy_;
      p.fxx[i] = fxx;
      p.fxy[i] = fxy;
      p.fyx[i] = fyx;
      p.fyy[i] = fyy;
      // Rotation of the polar decomposition F = R U (2D: one angle); only the
      // contact normals of surface particles with contact candidates use it.
      if (contact_rows && contact_rows[i] != contact_rows[i + 1] &&
          std::isfinite(p.surf_depth[i])) {
        p.rot[i] = std::atan2(fyx - fxy, fxx + fyy);
      }

      // Saint Venant-Kirchhoff, plane strain (E_zz = 0).
      const int b = p.body[i];
      const double lam = lambda_body[b], mu = mu_body[b];
      const double exx = 0.5 * (fxx * fxx + fyx * fyx - 1.0);
      const double eyy = 0.5 * (fxy * fxy + fyy * fyy - 1.0);
      const double exy = 0.5 * (fxx * fxy + fyx * fyy);
      const double tr = exx + eyy;
      const double sxx = lam * tr + 2 * mu * exx, syy = lam * tr + 2 * mu * eyy, sxy = 2 * mu * exy;
      const double szz = lam * tr;
      // P = F S
      const double pxx = fxx * sxx + fxy * sxy, pxy = fxx * sxy + fxy * syy;
      const double pyx = fyx * sxx + fyy * sxy, pyy = fyx * sxy + fyy * syy;
      rp.px[i] = pxx;
      rp.py[i] = pxy;
      rp.pyx[i] = pyx;
      rp.pyy[i] = pyy;
      // Cauchy sigma = F S F^T / J (sigma_zz = S_zz / J) for output.
      const double inv_jac = 1.0 / (fxx * fyy - fxy * fyx);
      const double cxx = (pxx * fxx + pxy * fxy) * inv_jac;
      const double cyy = (pyx * fyx + pyy * fyy) * inv_jac;
      const double cxy = (pxx * fyx + pxy * fyy) * inv_jac;
      const double czz = szz * inv_jac;
      const double mean = (cxx + cyy + czz) / 3.0;
      p.p[i] = -mean;
      p.sxx[i] = cxx - mean;
      p.syy[i] = cyy - mean;
      p.szz[i] = czz - mean;
      p.sxy[i] = cxy;
      p.rho[i] = p.rho0[i] * inv_jac;
    }
  }
}

namespace {

// Monaghan's viscosity of one pair (artificial_viscosity.hpp) over one
// denominator, without the neighbour's mass: Pi_ij dW/dr / r with
// Pi = h v.x (beta h v.x - alpha c q) / (q^2 rho), q = r^2 + eta^2, so the
// pair costs one square root and one division. Separating pairs (v.x >= 0)
// are not damped. Symmetric in i and j.
inline double viscosity_pair(double dw0, double h, double vr, double r2, double q, double alpha,
                             double beta, double c_mean, double rho_mean) {
  const double num = dw0 * h * vr * (beta * h * vr - alpha * c_mean * q);
  const double all = num / (q * q * rho_mean * std::sqrt(r2));
  return vr < 0.0 ? all : 0.0;
}

// The pair loop of the momentum equation, one instantiation with and one
// without hourglass control: raw pointers and no branches (the viscosity's
// switch is a select). The stress share is gathered row by row (each row
// writes only its own particle); the viscosity, which needs a square root
// and a division per pair, is evaluated once per unordered pair and added
// to both ends through per-thread sums (equal and opposite: momentum is
// conserved exactly). The row sums are left scalar on purpose: rows hold
// ~28 entries and every entry gathers a dozen neighbour values, so
// `omp simd` reductions cost more in gathers, masks and reduction set-up
// than they save (measured: 17 % slower here, 2.2x slower in the F loop;
// docs/speed-accuracy.md).
template <bool kHourglass>
void momentum_loop(Simulation& sim, double dt) {
  Particles& p = sim.particles;
  ReferencePairs& rp = sim.reference;
  const ArtificialViscosity& av = sim.method.viscosity;
  const double h = sim.h();
  const double hg = sim.method.hourglass.coefficient;
  const double alpha = av.alpha, beta = av.beta;
  const double eta2 = (av.eta_over_h * h) * (av.eta_over_h * h);
  const std::size_t n = p.n;
  const int threads = std::max(1, sim.threads);
  if (rp.pair_acc.size() != 2 * n * static_cast<std::size_t>(threads)) {
    rp.pair_acc.assign(2 * n * static_cast<std::size_t>(threads), 0.0);
  }
  double* pair_acc = rp.pair_acc.data();
  const std::uint32_t* rows = rp.rows.data();
  const std::uint32_t* upper = rp.upper.data();
  const std::uint32_t* jj = rp.j.data();
  const double *gjx = rp.gjx.data(), *gjy = rp.gjy.data();
  const double *dw0 = rp.dw0.data(), *w0 = rp.w0.data();
  const double *Pxx = rp.px.data(), *Pxy = rp.py.data();
  const double *Pyx = rp.pyx.data(), *Pyy = rp.pyy.data();
  const double *sgx = rp.sgx.data(), *sgy = rp.sgy.data();
  const double* vol0 = rp.vol0.data();
  const double *x = p.x.data(), *y = p.y.data(), *vx = p.vx.data(), *vy = p.vy.data();
  const double *x0 = p.x0.data(), *y0 = p.y0.data();
  const double *cs = p.cs.data(), *rho = p.rho.data(), *mass = p.mass.data();
  const double *Fxx = p.fxx.data(), *Fxy = p.fxy.data(), *Fyx = p.fyx.data(), *Fyy = p.fyy.data();
  double dissipated = 0.0;
#pragma omp parallel num_threads(threads) reduction(+ : dissipated)
  {
    // The team may be smaller than asked for: only its buffers are summed.
    const int team = omp_get_num_threads();
    double* acc_x = pair_acc + 2 * n * static_cast<std::size_t>(omp_get_thread_num());
    double* acc_y = acc_x + n;
    std::fill(acc_x, acc_x + 2 * n, 0.0);
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      const double inv_rho0 = 1.0 / p.rho0[i];
      const double e_mod = kHourglass ? sim.material_of(i).E : 0.0;
      const double xi = x[i], yi = y[i], vxi = vx[i], vyi = vy[i];
      const double csi = cs[i], rhoi = rho[i], mi = mass[i];
      // (P_i B_i + P_j B_j) grad0_i W_ij V0_j: the P_i share is P_i times the
      // row's gradient sum (setup), only the P_j share is summed over pairs.
      double sx = 0, sy = 0, ax = 0, ay = 0;
      for (std::uint32_t k = rows[i]; k < rows[i + 1]; ++k) {
        const std::uint32_t j = jj[k];
        sx += Pxx[j] * gjx[k] + Pxy[j] * gjy[k];
        sy += Pyx[j] * gjx[k] + Pyy[j] * gjy[k];
        if constexpr (kHourglass) {
          // Ganzenmueller 2015: penalise x_ij - F_mean X_ij along the pair.
          const double dx = xi - x[j], dy = yi - y[j];
          const double dvx = vxi - vx[j], dvy = vyi - vy[j];
          const double r2 = dx * dx + dy * dy;
          const double vol_j = vol0[j];
          const double X = x0[i] - x0[j], Y = y0[i] - y0[j];
          const double fxx = 0.5 * (Fxx[i] + Fxx[j]), fxy = 0.5 * (Fxy[i] + Fxy[j]);
          const double fyx = 0.5 * (Fyx[i] + Fyx[j]), fyy = 0.5 * (Fyy[i] + Fyy[j]);
          const double ex = dx - (fxx * X + fxy * Y), ey = dy - (fyx * X + fyy * Y);
          const double inv_r = 1.0 / std::sqrt(r2);
          const double stretch = (ex * dx + ey * dy) * inv_r;
          const double R2 = X * X + Y * Y;
          const double f = -0.5 * hg * e_mod * vol_j * inv_rho0 * w0[k] * stretch / R2 * inv_r;
          ax += f * dx;
          ay += f * dy;
          dissipated -= 0.5 * mi * f * (dvx * dx + dvy * dy);
        }
      }
      // Viscosity: each unordered pair once, from its lower index.
      for (std::uint32_t k = upper[i]; k < rows[i + 1]; ++k) {
        const std::uint32_t j = jj[k];
        const double dx = xi - x[j], dy = yi - y[j];
        const double dvx = vxi - vx[j], dvy = vyi - vy[j];
        const double r2 = dx * dx + dy * dy;
        const double vr = dvx * dx + dvy * dy;
        const double pg = viscosity_pair(dw0[k], h, vr, r2, r2 + eta2, alpha, beta,
                                         0.5 * (csi + cs[j]), 0.5 * (rhoi + rho[j]));
        const double mj = mass[j];
        acc_x[i] -= mj * pg * dx;
        acc_y[i] -= mj * pg * dy;
        acc_x[j] += mi * pg * dx;
        acc_y[j] += mi * pg * dy;
        dissipated += mi * mj * pg * vr;  // >= 0: energy removed
      }
      const double pxx = Pxx[i], pxy = Pxy[i], pyx = Pyx[i], pyy = Pyy[i];
      p.ax[i] = ax + inv_rho0 * (pxx * sgx[i] + pxy * sgy[i] + sx);
      p.ay[i] = ay + inv_rho0 * (pyx * sgx[i] + pyy * sgy[i] + sy);
    }
    // (implicit barrier: every thread's pair sums are complete)
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      double ax = 0, ay = 0;
      for (int t = 0; t < team; ++t) {
        ax += pair_acc[2 * n * static_cast<std::size_t>(t) + i];
        ay += pair_acc[2 * n * static_cast<std::size_t>(t) + n + i];
      }
      p.ax[i] += ax;
      p.ay[i] += ay;
    }
  }
  sim.energy.dissipated += dt * dissipated;
}

}  // namespace

void total_lagrangian_momentum(Simulation& sim, double dt) {
  if (sim.method.hourglass.enabled()) {
    if (sim.reference.w0.size() != sim.reference.j.size()) {
      throw std::logic_error("hourglass control switched on after total_lagrangian_setup");
    }
    momentum_loop<true>(sim, dt);
  } else {
    momentum_loop<false>(sim, dt);
  }
}

}  // namespace gearsph::physics
