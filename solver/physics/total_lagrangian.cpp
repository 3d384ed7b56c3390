#include "solver/physics/total_lagrangian.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "solver/core/simulation.hpp"
#include "solver/physics/artificial_viscosity.hpp"
#include "solver/physics/contact.hpp"
#include "solver/physics/elastic_law.hpp"

namespace gearsph::physics {

namespace {

// Values a pair writes to each end: F loop 4 (the sum M of F = I + M),
// momentum loop 6 (stress share, viscosity, hourglass).
constexpr int kDeformationSpill = 4;
constexpr int kMomentumSpill = 6;

// What a row costs besides its pairs, in pairs of its own pass: measured on
// the paper's gear, one thread (docs/speed-accuracy.md, sixth round). A pair
// costs the F pass 2.6 ns and a row the stress pass 10.6 ns; a pair costs
// the momentum pass 4.9 ns, and as much again when it approaches (the
// division, the square root, the branch's mispredictions), and a row the
// accelerations, loads and kicks 14 ns. The tenth round found the
// division, square root and branch alone worth only ~2 % of the step on one
// thread; a weight of 1.5 for an approaching pair balanced the threads no
// better than 1.0 within the runs' spread, so the weight was left as
// measured in the sixth round.
constexpr double kStressRowCost = 4.0;
constexpr double kMomentumRowCost = 3.0;
constexpr double kApproachingPairCost = 1.0;

// The momentum cut is made at the start by pairs and rows, and again every
// kReplanSteps steps with each row's approaching pairs (v_ij . x_ij < 0,
// counted by the last momentum pass) weighted. In the meshing gear 52 % of
// the pinion's pairs approach against 28-34 % of the rack's; cut by pairs
// alone, the thread holding the pinion took 14-20 % longer over the
// momentum pass (docs/speed-accuracy.md, fifth round). The counts are a
// function of the state, not of timing, so a run repeats bit for bit; a new
// cut changes which sums spill, so the round-off. The deformation cut never
// changes: the reference pairs do not.
constexpr long kReplanSteps = 1024;

// The momentum pass counts the approaching pairs only in the step before a
// new cut, the one whose counts the cut reads (planned_chunks is called
// with the next step's number), not in the other 1,023 (about 1 % of the
// gear's step on one thread).
bool count_approaching(long step) {
  return (step + 1) % kReplanSteps == 0;
}

// Four sums of one particle as one vector (GCC's vector extension: one
// AVX register). A pair adds its four values to its far end with one load,
// one fused multiply-add and one store, where four scattered sums took a
// quarter of the momentum pass (docs/speed-accuracy.md, tenth round).
using Four = double __attribute__((vector_size(4 * sizeof(double))));

// to[0..3] += a * b, each lane rounded once, as the scalar to += a * b is
// (and to += a exactly where b is 1). By reference: no vector in the
// function's signature, so no ABI to depend on the instruction set.
inline void add_product(double* to, const Four& a, const Four& b) {
  Four sum;
  std::memcpy(&sum, to, sizeof sum);
  sum = a * b + sum;
  std::memcpy(to, &sum, sizeof sum);
}

struct Cuts {
  RowChunks& deformation;
  RowChunks& momentum;
};

Cuts planned_chunks(Simulation& sim, long step) {
  ReferencePairs& rp = sim.reference;
  const int threads = std::max(1, sim.threads);
  if (!rp.deformation_chunks.planned_for(threads, kDeformationSpill)) {
    rp.deformation_chunks.plan(rp.rows, rp.j, threads, kDeformationSpill, {kStressRowCost});
    rp.chunk_peaks.assign(threads, {});
  }
  const bool first = !rp.momentum_chunks.planned_for(threads, kMomentumSpill);
  const bool due = threads > 1 && step % kReplanSteps == 0 && step != rp.planned_step;
  if (first || due) {
    const bool counted = rp.approaching.size() + 1 == rp.rows.size();
    rp.momentum_chunks.plan(
        rp.rows, rp.j, threads, kMomentumSpill,
        {kMomentumRowCost, counted ? rp.approaching.data() : nullptr, kApproachingPairCost});
    rp.planned_step = step;
  }
  return {rp.deformation_chunks, rp.momentum_chunks};
}

// F loop, pass 0 for chunk c: displacements u = x - X, so that the pair
// loop gathers two values per neighbour instead of four.
void displacements(Simulation& sim, const RowChunks& chunks, int c) {
  const Particles& p = sim.particles;
  ReferencePairs& rp = sim.reference;
  for (std::size_t i = chunks.begin(c); i < chunks.end(c); ++i) {
    rp.ux[i] = p.x[i] - p.x0[i];
    rp.uy[i] = p.y[i] - p.y0[i];
  }
}

// F loop, pass 1 for chunk c, each pair once: M_i += V0_j (u_j - u_i) (x) G_ij
// and M_j += V0_i (u_i - u_j) (x) G_ji, with displacements u = x - X so that
// round-off does not swamp strains of 1e-6 on positions of 1e-1 m (the small
// terms are summed first, then added to I).
void deformation_pairs(Simulation& sim, RowChunks& chunks, int c) {
  const ReferencePairs& rp = sim.reference;
  const std::uint32_t* rows = rp.rows.data();
  const std::uint32_t* jj = rp.j.data();
  const double *gix = rp.gix.data(), *giy = rp.giy.data();
  const double *gjx = rp.gjx.data(), *gjy = rp.gjy.data();
  const double* vol0 = rp.vol0.data();
  const double *ux = rp.ux.data(), *uy = rp.uy.data();
  // M = F - I, xx, xy, yx, yy side by side (ReferencePairs::sums).
  double* const sums = sim.reference.sums.data();
  const std::size_t lo = chunks.begin(c), hi = chunks.end(c);
  std::fill(sums + 4 * lo, sums + 4 * hi, 0.0);
  double* const spill = chunks.spill_grouped(c);
  for (std::size_t i = lo; i < hi; ++i) {
    const double uxi = ux[i], uyi = uy[i], vi = vol0[i];
    // Row i continues the sums its pairs with j < i began.
    double mxx = sums[4 * i], mxy = sums[4 * i + 1], myx = sums[4 * i + 2], myy = sums[4 * i + 3];
    auto pairs = [&](std::uint32_t k0, std::uint32_t k1, double* to, std::size_t base) {
      for (std::uint32_t k = k0; k < k1; ++k) {
        const std::uint32_t j = jj[k];
        const double dux = ux[j] - uxi, duy = uy[j] - uyi;
        const double vj = vol0[j];
        const double ax = vj * gix[k], ay = vj * giy[k];
        mxx += dux * ax;
        mxy += dux * ay;
        myx += duy * ax;
        myy += duy * ay;
        const double bx = vi * gjx[k], by = vi * gjy[k];
        // M_j += (u_i - u_j) (x) V0_i G_ji
        add_product(to + 4 * (j - base), Four{-dux, -dux, -duy, -duy}, Four{bx, by, bx, by});
      }
    };
    pairs(rows[i], chunks.cross(i), sums, 0);        // j in this chunk
    pairs(chunks.cross(i), rows[i + 1], spill, hi);  // j past it
    sums[4 * i] = mxx;
    sums[4 * i + 1] = mxy;
    sums[4 * i + 2] = myx;
    sums[4 * i + 3] = myy;
  }
}

// F loop, pass 2 for chunk c, per particle: F, then P and the Cauchy stress.
void stress_per_particle(Simulation& sim, RowChunks& chunks, int c) {
  Particles& p = sim.particles;
  ReferencePairs& rp = sim.reference;
  const double* lambda_body = rp.lambda_body.data();
  const double* mu_body = rp.mu_body.data();
  const double* const m_sum = rp.sums.data();  // M = F - I (deformation_pairs)
  // Raw pointers, as in the pair loops: no reload of an array's address
  // after each store.
  double *Fxx = p.fxx.data(), *Fxy = p.fxy.data(), *Fyx = p.fyx.data(), *Fyy = p.fyy.data();
  double *Pxx = rp.px.data(), *Pxy = rp.py.data(), *Pyx = rp.pyx.data(), *Pyy = rp.pyy.data();
  double *pressure = p.p.data(), *Sxx = p.sxx.data(), *Syy = p.syy.data();
  double *Szz = p.szz.data(), *Sxy = p.sxy.data(), *rho = p.rho.data();
  const double *rho0 = p.rho0.data(), *surf_depth = p.surf_depth.data();
  const double* vol0 = rp.vol0.data();
  const std::int32_t* body = p.body.data();
  // Contact candidates (penalty contact only), refreshed before this step's
  // forces, and their normals' scratch (sized when the list was built).
  const std::uint32_t* contact_rows =
      sim.contacts.rows.size() == p.n + 1 ? sim.contacts.rows.data() : nullptr;
  ContactState& touch = sim.contact_state;
  const bool normals = contact_rows && touch.normal_x.size() == p.n;
  chunks.add_spills_grouped(c, rp.sums.data(), 4);
  const std::size_t lo = chunks.begin(c), hi = chunks.end(c);
  // The stress of a block of particles as one vectorised loop; then, in
  // order, the block's largest J2 (first particle on ties, as a scan finds
  // it) from a buffer on the stack. A branch or a running maximum in the
  // loop would keep it scalar (this pass cost 10 % of the gear's step).
  constexpr std::size_t kBlock = 64;
  double j2_block[kBlock];
  double j2_max = 0.0;
  long peak = -1;
  for (std::size_t b0 = lo; b0 < hi; b0 += kBlock) {
    const std::size_t b1 = std::min(hi, b0 + kBlock);
#pragma omp simd
    for (std::size_t i = b0; i < b1; ++i) {
      const double fxx = 1.0 + m_sum[4 * i], fxy = m_sum[4 * i + 1];
      const double fyx = m_sum[4 * i + 2], fyy = 1.0 + m_sum[4 * i + 3];
      Fxx[i] = fxx;
      Fxy[i] = fxy;
      Fyx[i] = fyx;
      Fyy[i] = fyy;
      const int b = body[i];
      const SecondPiola s =
          saint_venant_kirchhoff(green_lagrange(fxx, fxy, fyx, fyy), lambda_body[b], mu_body[b]);
      const double sxx = s.xx, syy = s.yy, sxy = s.xy, szz = s.zz;
      // P = F S
      const double pxx = fxx * sxx + fxy * sxy, pxy = fxx * sxy + fxy * syy;
      const double pyx = fyx * sxx + fyy * sxy, pyy = fyx * sxy + fyy * syy;
      // Kept times the reference volume (ReferencePairs::px).
      const double v0 = vol0[i];
      Pxx[i] = v0 * pxx;
      Pxy[i] = v0 * pxy;
      Pyx[i] = v0 * pyx;
      Pyy[i] = v0 * pyy;
      // Cauchy sigma = F S F^T / J (sigma_zz = S_zz / J) for output.
      const double inv_jac = 1.0 / (fxx * fyy - fxy * fyx);
      const double cxx = (pxx * fxx + pxy * fxy) * inv_jac;
      const double cyy = (pyx * fyx + pyy * fyy) * inv_jac;
      const double cxy = (pxx * fyx + pxy * fyy) * inv_jac;
      const double czz = szz * inv_jac;
      const double mean = (cxx + cyy + czz) / 3.0;
      const double dxx = cxx - mean, dyy = cyy - mean, dzz = czz - mean;
      pressure[i] = -mean;
      Sxx[i] = dxx;
      Syy[i] = dyy;
      Szz[i] = dzz;
      Sxy[i] = cxy;
      rho[i] = rho0[i] * inv_jac;
      j2_block[i - b0] = 0.5 * (dxx * dxx + dyy * dyy + dzz * dzz) + cxy * cxy;  // Particles::j2
    }
    for (std::size_t i = b0; i < b1; ++i) {
      if (j2_block[i - b0] > j2_max) {
        j2_max = j2_block[i - b0];
        peak = static_cast<long>(i);
      }
    }
  }
  // The contact normals of surface particles with contact candidates turn
  // with the rotation of the polar decomposition F = R U: in 2D
  // R = [[c, -s], [s, c]] with (c, s) along (F_xx + F_yy, F_yx - F_xy).
  // A square root and a division, where an angle cost atan2, sin and cos.
  // As a masked vector loop: a branch per particle mispredicted along the
  // mesh zone, and left the thread holding it 2 us a step behind.
  if (normals) {
    constexpr double kMaxDepth = std::numeric_limits<double>::max();
    const double *nx0 = p.surf_nx.data(), *ny0 = p.surf_ny.data();
    double *nx = touch.normal_x.data(), *ny = touch.normal_y.data();
#pragma omp simd
    for (std::size_t i = lo; i < hi; ++i) {
      const double a = Fxx[i] + Fyy[i], b = Fyx[i] - Fxy[i];
      const double inv = 1.0 / std::sqrt(a * a + b * b);
      // Interior particles have depth +inf and no normal.
      if (contact_rows[i] != contact_rows[i + 1] && std::abs(surf_depth[i]) <= kMaxDepth) {
        turn_normal(a * inv, b * inv, nx0[i], ny0[i], nx[i], ny[i]);
      }
    }
  }
  rp.chunk_peaks[c] = {j2_max, peak};
}

// The pair loop of the momentum equation, instantiated with and without
// hourglass control and the count of approaching pairs: raw pointers, and
// no branch but the viscosity's (above). Each pair once, written to both ends (RowChunks):
//   stress share  a_i += -V0_j P_j G_ji / rho0_i,  a_j += -V0_i P_i G_ij / rho0_j
//   viscosity     a_i -= m_j Pi_ij g_ij,           a_j += m_i Pi_ij g_ij
// (equal and opposite: momentum is conserved exactly). The own share
// P_i sum_j V0_j G_ij needs no pair work (sgx, sgy). The row sums are left
// scalar on purpose: `omp simd` reductions over gathered neighbours cost more
// in gathers, masks and set-up than they save (measured: 17 % slower here,
// 2.2x slower in the F loop; docs/speed-accuracy.md).
// Momentum loop, pass 1 for chunk c; returns the energy the hourglass
// control removed per unit time (the viscosity's: accelerations_per_particle).
template <bool kHourglass, bool kCount, bool kUniform, bool kGraded>
double momentum_pairs_of(Simulation& sim, RowChunks& chunks, int c) {
  Particles& p = sim.particles;
  ReferencePairs& rp = sim.reference;
  const double mass_all = rp.uniform.mass, cs_all = rp.uniform.cs;
  const ArtificialViscosity& av = sim.method.viscosity;
  const double h = sim.h();
  const double hg = sim.method.hourglass.coefficient;
  const double alpha = av.alpha, beta = av.beta;
  const double eta2 = (av.eta_over_h * h) * (av.eta_over_h * h);
  // Graded particles (kGraded): the pair's own h_ij = (h_i + h_j) / 2.
  const double* hp = rp.hp.data();
  const double eta_over_h2 = av.eta_over_h * av.eta_over_h;
  const std::uint32_t* rows = rp.rows.data();
  const std::uint32_t* jj = rp.j.data();
  const double *gix = rp.gix.data(), *giy = rp.giy.data();
  const double *gjx = rp.gjx.data(), *gjy = rp.gjy.data();
  const double *dw0 = rp.dw0.data(), *w0 = rp.w0.data();
  const double* e_over_rho0 = rp.e_over_rho0.data();
  const double *Pxx = rp.px.data(), *Pxy = rp.py.data();
  const double *Pyx = rp.pyx.data(), *Pyy = rp.pyy.data();
  const double* vol0 = rp.vol0.data();
  const double *x = p.x.data(), *y = p.y.data(), *vx = p.vx.data(), *vy = p.vy.data();
  const double *x0 = p.x0.data(), *y0 = p.y0.data();
  const double *cs = p.cs.data(), *rho = p.rho.data(), *mass = p.mass.data();
  const double *Fxx = p.fxx.data(), *Fxy = p.fxy.data(), *Fyx = p.fyx.data(), *Fyy = p.fyy.data();
  // Sums per particle: stress share and viscosity side by side (4 i + q),
  // hourglass apart (components 4 and 5 of the spill window).
  double* const sums = rp.sums.data();
  double* const hg_sum[2] = {rp.hg_ax.data(), rp.hg_ay.data()};
  double dissipated = 0.0;
  const std::size_t lo = chunks.begin(c), hi = chunks.end(c);
  std::fill(sums + 4 * lo, sums + 4 * hi, 0.0);
  double* const spill = chunks.spill_grouped(c);
  double* hg_spill[2] = {};
  if constexpr (kHourglass) {
    for (int q = 0; q < 2; ++q) {
      std::fill(hg_sum[q] + lo, hg_sum[q] + hi, 0.0);
      hg_spill[q] = chunks.spill(c, 4 + q);
    }
  }
  for (std::size_t i = lo; i < hi; ++i) {
    const double e_mod = kHourglass ? e_over_rho0[i] : 0.0;
    const double xi = x[i], yi = y[i], vxi = vx[i], vyi = vy[i];
    const double csi = cs[i], rhoi = rho[i], mi = mass[i], vi = vol0[i];
    const double qxx = Pxx[i], qxy = Pxy[i], qyx = Pyx[i], qyy = Pyy[i];  // V0_i P_i
    // Row i continues the sums its pairs with j < i began.
    double sx = sums[4 * i], sy = sums[4 * i + 1], vsx = sums[4 * i + 2], vsy = sums[4 * i + 3];
    double hsx = kHourglass ? hg_sum[0][i] : 0.0, hsy = kHourglass ? hg_sum[1][i] : 0.0;
    std::uint32_t approaching = 0;
    // Inlined by force: with hourglass control GCC kept this lambda out of
    // line, its sums and array addresses went through the closure to memory
    // at every pair, and the control cost 3.6 times the pass instead of 2
    // (docs/speed-accuracy.md).
    auto pairs = [&](std::uint32_t k0, std::uint32_t k1, double* to, double* const* hg_to,
                     std::size_t base) __attribute__((always_inline)) {
      for (std::uint32_t k = k0; k < k1; ++k) {
        const std::uint32_t j = jj[k];
        const std::size_t t = j - base;
        const double bx = gjx[k], by = gjy[k];  // G_ji
        sx -= Pxx[j] * bx + Pxy[j] * by;        // V0_j P_j G_ji
        sy -= Pyx[j] * bx + Pyy[j] * by;
        const double ax = gix[k], ay = giy[k];  // G_ij
        const double share_x = -(qxx * ax + qxy * ay), share_y = -(qyx * ax + qyy * ay);
        const double dx = xi - x[j], dy = yi - y[j];
        const double dvx = vxi - vx[j], dvy = vyi - vy[j];
        const double r2 = dx * dx + dy * dy;
        const double vr = dvx * dx + dvy * dy;
        const double cs_mean = kUniform ? cs_all : 0.5 * (csi + cs[j]);
        double pg;
        if constexpr (kGraded) {
          const double hij = 0.5 * (hp[i] + hp[j]);
          pg = viscosity_pair(dw0[k], hij, vr, r2, r2 + eta_over_h2 * hij * hij, alpha, beta,
                              cs_mean, 0.5 * (rhoi + rho[j]));
        } else {
          pg = viscosity_pair(dw0[k], h, vr, r2, r2 + eta2, alpha, beta, cs_mean,
                              0.5 * (rhoi + rho[j]));
        }
        if constexpr (kCount) approaching += vr < 0.0 ? 1 : 0;
        const double mj = kUniform ? mass_all : mass[j];
        vsx -= mj * pg * dx;
        vsy -= mj * pg * dy;
        // j's stress share and viscosity: += share * 1 and += (m_i pg) x_ij.
        const double mpg = mi * pg;
        add_product(to + 4 * t, Four{share_x, share_y, mpg, mpg}, Four{1.0, 1.0, dx, dy});
        if constexpr (kHourglass) {
          // Ganzenmueller 2015, eqs. (23)-(27): the pair's stretch that the
          // mean deformation gradient does not explain, e = x_ij - F_mean
          // X_ij, pulled back along the pair with the stiffness
          // hg E_i V_j W / (2 |X|^2 rho0_i), times e . x_ij / r^2 (the
          // stretch per length along the unit pair twice: no square root).
          // w0 holds W / (2 |X|^2), e_over_rho0 E / rho0 (set-up).
          const double X = x0[i] - x0[j], Y = y0[i] - y0[j];
          const double fxx = 0.5 * (Fxx[i] + Fxx[j]), fxy = 0.5 * (Fxy[i] + Fxy[j]);
          const double fyx = 0.5 * (Fyx[i] + Fyx[j]), fyy = 0.5 * (Fyy[i] + Fyy[j]);
          const double ex = dx - (fxx * X + fxy * Y), ey = dy - (fyx * X + fyy * Y);
          const double common = -hg * w0[k] * (ex * dx + ey * dy) / r2;
          const double fi = common * e_mod * vol0[j];
          const double fj = common * e_over_rho0[j] * vi;
          hsx += fi * dx;
          hsy += fi * dy;
          hg_to[0][t] += fj * -dx;
          hg_to[1][t] += fj * -dy;
          dissipated -= 0.5 * (mi * fi + mj * fj) * vr;
        }
      }
    };
    pairs(rows[i], chunks.cross(i), sums, hg_sum, 0);          // j in this chunk
    pairs(chunks.cross(i), rows[i + 1], spill, hg_spill, hi);  // j past it
    sums[4 * i] = sx;
    sums[4 * i + 1] = sy;
    sums[4 * i + 2] = vsx;
    sums[4 * i + 3] = vsy;
    if constexpr (kHourglass) {
      hg_sum[0][i] = hsx;
      hg_sum[1][i] = hsy;
    }
    if constexpr (kCount) rp.approaching[i] = approaching;
  }
  return dissipated;
}

template <bool kHourglass>
double momentum_pairs(Simulation& sim, RowChunks& chunks, int c) {
  const bool count = count_approaching(sim.step);
  if (sim.reference.uniform.all) {
    return count ? momentum_pairs_of<kHourglass, true, true, false>(sim, chunks, c)
                 : momentum_pairs_of<kHourglass, false, true, false>(sim, chunks, c);
  }
  if (!sim.reference.hp.empty()) {
    return count ? momentum_pairs_of<kHourglass, true, false, true>(sim, chunks, c)
                 : momentum_pairs_of<kHourglass, false, false, true>(sim, chunks, c);
  }
  return count ? momentum_pairs_of<kHourglass, true, false, false>(sim, chunks, c)
               : momentum_pairs_of<kHourglass, false, false, false>(sim, chunks, c);
}

// Momentum loop, pass 2 for chunk c, per particle: the own share
// P_i sum_j V0_j G_ij, then a = sum / rho0 plus viscosity and hourglass.
// Returns the power the viscosity removes, -sum_i m_i v_i . a_visc_i: the
// pairs' sum m_i m_j Pi_ij g_ij . v_ij regrouped by particle, at one
// product a particle instead of three a pair (the same velocities: the
// closing kick comes after).
template <bool kHourglass>
double accelerations_per_particle(Simulation& sim, RowChunks& chunks, int c) {
  Particles& p = sim.particles;
  ReferencePairs& rp = sim.reference;
  const double *Pxx = rp.px.data(), *Pxy = rp.py.data();
  const double *Pyx = rp.pyx.data(), *Pyy = rp.pyy.data();
  const double *sgx = rp.sgx.data(), *sgy = rp.sgy.data();
  const double* rho0 = p.rho0.data();
  const double* const sums = rp.sums.data();
  double* const hg_sum[2] = {rp.hg_ax.data(), rp.hg_ay.data()};
  double *ax = p.ax.data(), *ay = p.ay.data();
  const double *vx = p.vx.data(), *vy = p.vy.data(), *mass = p.mass.data();
  chunks.add_spills_grouped(c, rp.sums.data(), 4);
  if constexpr (kHourglass) chunks.add_spills(c, hg_sum, 2, 4);
  double viscous = 0.0;
  const std::size_t lo = chunks.begin(c), hi = chunks.end(c);
  // A vector loop: the power summed as a simd reduction (a scalar sum kept
  // the loop, and its division, scalar).
#pragma omp simd reduction(+ : viscous)
  for (std::size_t i = lo; i < hi; ++i) {
    const double inv_rho0 = 1.0 / rho0[i];
    const double hx = kHourglass ? hg_sum[0][i] : 0.0, hy = kHourglass ? hg_sum[1][i] : 0.0;
    ax[i] = hx + inv_rho0 * (Pxx[i] * sgx[i] + Pxy[i] * sgy[i] + sums[4 * i]);
    ay[i] = hy + inv_rho0 * (Pyx[i] * sgx[i] + Pyy[i] * sgy[i] + sums[4 * i + 1]);
    ax[i] += sums[4 * i + 2];
    ay[i] += sums[4 * i + 3];
    viscous -= mass[i] * (vx[i] * sums[4 * i + 2] + vy[i] * sums[4 * i + 3]);
  }
  return viscous;
}

template <bool kHourglass>
void momentum(Simulation& sim, double dt) {
  RowChunks& rows = planned_chunks(sim, sim.step).momentum;
  double dissipated = 0.0;
#pragma omp parallel num_threads(rows.chunks()) reduction(+ : dissipated)
  {
    for_my_chunks(rows, [&](int c) { dissipated += momentum_pairs<kHourglass>(sim, rows, c); });
#pragma omp barrier
    for_my_chunks(
        rows, [&](int c) { dissipated += accelerations_per_particle<kHourglass>(sim, rows, c); });
  }
  sim.energy.dissipated += dt * dissipated;
}

// Stress and momentum in one parallel region: three barriers a step.
template <bool kHourglass>
void stress_and_momentum(Simulation& sim, double dt) {
  const Cuts cut = planned_chunks(sim, sim.step);
  RowChunks &f_rows = cut.deformation, &m_rows = cut.momentum;
  double dissipated = 0.0;
#pragma omp parallel num_threads(f_rows.chunks()) reduction(+ : dissipated)
  {
    for_my_chunks(f_rows, [&](int c) { displacements(sim, f_rows, c); });
#pragma omp barrier
    for_my_chunks(f_rows, [&](int c) { deformation_pairs(sim, f_rows, c); });
#pragma omp barrier
    for_my_chunks(f_rows, [&](int c) { stress_per_particle(sim, f_rows, c); });
#pragma omp barrier
    for_my_chunks(m_rows, [&](int c) { dissipated += momentum_pairs<kHourglass>(sim, m_rows, c); });
#pragma omp barrier
    for_my_chunks(m_rows, [&](int c) {
      dissipated += accelerations_per_particle<kHourglass>(sim, m_rows, c);
    });
  }
  sim.energy.dissipated += dt * dissipated;
  gather_largest_j2(sim);
}

bool hourglass_ready(const Simulation& sim) {
  if (!sim.method.hourglass.enabled()) return false;
  if (sim.reference.w0.size() != sim.reference.j.size() ||
      sim.reference.hg_ax.size() != sim.particles.n) {
    throw std::logic_error("hourglass control switched on after total_lagrangian_setup");
  }
  return true;
}

}  // namespace

void total_lagrangian_stress(Simulation& sim) {
  RowChunks& rows = planned_chunks(sim, sim.step).deformation;
#pragma omp parallel num_threads(rows.chunks())
  {
    for_my_chunks(rows, [&](int c) { displacements(sim, rows, c); });
#pragma omp barrier
    for_my_chunks(rows, [&](int c) { deformation_pairs(sim, rows, c); });
#pragma omp barrier
    for_my_chunks(rows, [&](int c) { stress_per_particle(sim, rows, c); });
  }
  gather_largest_j2(sim);
}

void total_lagrangian_momentum(Simulation& sim, double dt) {
  if (hourglass_ready(sim)) {
    momentum<true>(sim, dt);
  } else {
    momentum<false>(sim, dt);
  }
}

void gather_largest_j2(Simulation& sim) {
  const ReferencePairs& rp = sim.reference;
  LargestJ2 largest;
  for (const ReferencePairs::ChunkPeak& c : rp.chunk_peaks) {  // in row order
    if (c.j2 > largest.j2) {
      largest.j2 = c.j2;
      largest.particle = c.particle;
    }
  }
  largest.step = sim.step;
  sim.largest_j2 = largest;
}

TotalLagrangianPasses total_lagrangian_passes(Simulation& sim) {
  const bool hourglass = hourglass_ready(sim);
  const Cuts cut = planned_chunks(sim, sim.step + 1);  // before the clock advances
  return {cut.deformation, cut.momentum, hourglass};
}

void deformation_sums(Simulation& sim, TotalLagrangianPasses& tl, int c) {
  deformation_pairs(sim, tl.deformation, c);
}

void stress_from_deformation(Simulation& sim, TotalLagrangianPasses& tl, int c) {
  stress_per_particle(sim, tl.deformation, c);
}

double momentum_sums(Simulation& sim, TotalLagrangianPasses& tl, int c) {
  return tl.hourglass ? momentum_pairs<true>(sim, tl.momentum, c)
                      : momentum_pairs<false>(sim, tl.momentum, c);
}

double accelerations(Simulation& sim, TotalLagrangianPasses& tl, int c) {
  return tl.hourglass ? accelerations_per_particle<true>(sim, tl.momentum, c)
                      : accelerations_per_particle<false>(sim, tl.momentum, c);
}

void total_lagrangian_forces(Simulation& sim, double dt) {
  if (hourglass_ready(sim)) {
    stress_and_momentum<true>(sim, dt);
  } else {
    stress_and_momentum<false>(sim, dt);
  }
}

}  // namespace gearsph::physics
