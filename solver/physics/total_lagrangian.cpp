#include "solver/physics/total_lagrangian.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <span>
#include <stdexcept>

#include "solver/core/passes.hpp"
#include "solver/physics/artificial_viscosity.hpp"
#include "solver/physics/contact.hpp"
#include "solver/physics/elastic_law.hpp"
#include "solver/physics/hourglass.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph::physics {

namespace {

// Values a pair writes to each end: F loop 4 (the sum M of F = I + M),
// momentum loop 6 (stress share, viscosity, hourglass).
constexpr int kDeformationSpill = 4;
constexpr int kMomentumSpill = 6;

constexpr std::size_t kNeverStop = 0;

// What a row costs besides its pairs, in pairs of its own pass: measured
// on the seed paper's gear, one thread (docs/speed-accuracy-history.md, "a cut for
// each pair pass"). Every pair of a pass costs the same: the viscosity has
// no branch (artificial_viscosity.hpp, viscosity_pair).
constexpr double kStressRowCost = 4.0;
constexpr double kMomentumRowCost = 3.0;

// Four sums of one particle as one vector (GCC's vector extension: one
// AVX register). A pair adds its four values to its far end with one load,
// one fused multiply-add and one store instead of four scattered sums
// (docs/speed-accuracy-history.md, "a pair's four sums to its far end").
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

// Cut once per run and thread count: the reference pairs never change.
Cuts planned_chunks(Simulation& sim) {
  ReferencePairs& rp = sim.reference;
  const int threads = std::max(1, sim.threads);
  if (!rp.deformation_chunks.planned_for(threads, kDeformationSpill)) {
    rp.deformation_chunks.plan(rp.rows, rp.j, threads, kDeformationSpill, {kStressRowCost});
    rp.chunk_peaks.assign(threads, {});
  }
  if (!rp.momentum_chunks.planned_for(threads, kMomentumSpill)) {
    rp.momentum_chunks.plan(rp.rows, rp.j, threads, kMomentumSpill, {kMomentumRowCost});
  }
  return {rp.deformation_chunks, rp.momentum_chunks};
}

// F loop, pass 1 for chunk c, each pair once: M_i += V0_j (u_j - u_i) (x) G_ij
// and M_j += V0_i (u_i - u_j) (x) G_ji, with displacements u = x - X so that
// round-off does not swamp strains of 1e-6 on positions of 1e-1 m (the small
// terms are summed first, then added to I).
void deformation_pairs(Simulation& sim, RowChunks& chunks, int c) {
  const ReferencePairs& rp = sim.reference;
  const std::uint32_t* rows = rp.rows.data();
  const std::uint32_t* jj = rp.j.data();
  const double* g = rp.g.data();  // G_ij x, y, G_ji x, y
  const double* u = rp.u.data();  // ux, uy, V0
  // M = F - I, xx, xy, yx, yy side by side (ReferencePairs::sums).
  double* const sums = sim.reference.sums.data();
  const std::size_t lo = chunks.begin(c), hi = chunks.end(c);
  std::fill(sums + 4 * lo, sums + 4 * hi, 0.0);
  double* const spill = chunks.spill_grouped(c);
  for (std::size_t i = lo; i < hi; ++i) {
    const double uxi = u[4 * i], uyi = u[4 * i + 1], vi = u[4 * i + 2];
    // Row i continues the sums its pairs with j < i began.
    double mxx = sums[4 * i], mxy = sums[4 * i + 1], myx = sums[4 * i + 2], myy = sums[4 * i + 3];
    auto pairs = [&](std::uint32_t k0, std::uint32_t k1, double* to, std::size_t base) {
      for (std::uint32_t k = k0; k < k1; ++k) {
        const std::uint32_t j = jj[k];
        const double* const uj = u + 4 * j;
        const double dux = uj[0] - uxi, duy = uj[1] - uyi;
        const double vj = uj[2];
        const double ax = vj * g[4 * k], ay = vj * g[4 * k + 1];
        mxx += dux * ax;
        mxy += dux * ay;
        myx += duy * ax;
        myy += duy * ay;
        const double bx = vi * g[4 * k + 2], by = vi * g[4 * k + 3];
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

// F loop, pass 2 for chunk c, per particle: F, then P and the Cauchy stress
// (Saint Venant-Kirchhoff, elastic_law.hpp), as one vectorised loop.
void stress_per_particle(Simulation& sim, RowChunks& chunks, int c) {
  Particles& p = sim.particles;
  ReferencePairs& rp = sim.reference;
  const double* lambda_body = rp.lambda_body.data();
  const double* mu_body = rp.mu_body.data();
  const double* const m_sum = rp.sums.data();  // M = F - I (deformation_pairs)
  // Raw pointers, as in the pair loops: no reload of an array's address
  // after each store.
  double *Fxx = p.fxx.data(), *Fxy = p.fxy.data(), *Fyx = p.fyx.data(), *Fyy = p.fyy.data();
  double* pv = rp.pv.data();
  double* state = rp.state.data();
  const double *x = p.x.data(), *y = p.y.data(), *vx = p.vx.data(), *vy = p.vy.data();
  double *pressure = p.p.data(), *Sxx = p.sxx.data(), *Syy = p.syy.data();
  double *Szz = p.szz.data(), *Sxy = p.sxy.data(), *rho = p.rho.data();
  const double* rho0 = p.rho0.data();
  const double* vol0 = rp.vol0.data();
  const std::int32_t* body = p.body.data();
  chunks.add_spills_grouped(c, rp.sums.data(), 4);
  const std::size_t lo = chunks.begin(c), hi = chunks.end(c);
#pragma omp simd
  for (std::size_t i = lo; i < hi; ++i) {
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
    // Kept times the reference volume (ReferencePairs::pv).
    const double v0 = vol0[i];
    pv[4 * i] = v0 * pxx;
    pv[4 * i + 1] = v0 * pxy;
    pv[4 * i + 2] = v0 * pyx;
    pv[4 * i + 3] = v0 * pyy;
    // Where the momentum pass gathers them (ReferencePairs::state).
    state[4 * i] = x[i];
    state[4 * i + 1] = y[i];
    state[4 * i + 2] = vx[i];
    state[4 * i + 3] = vy[i];
    // Cauchy sigma = F S F^T / J (sigma_zz = S_zz / J) for output.
    const double inv_jac = 1.0 / (fxx * fyy - fxy * fyx);
    const double cxx = (pxx * fxx + pxy * fxy) * inv_jac;
    const double cyy = (pyx * fyx + pyy * fyy) * inv_jac;
    const double cxy = (pxx * fyx + pxy * fyy) * inv_jac;
    const double czz = szz * inv_jac;
    const double mean = (cxx + cyy + czz) / 3.0;
    pressure[i] = -mean;
    Sxx[i] = cxx - mean;
    Syy[i] = cyy - mean;
    Szz[i] = czz - mean;
    Sxy[i] = cxy;
    rho[i] = rho0[i] * inv_jac;
  }
}

// The momentum pass's packed positions and velocities for chunk c, where
// no stress pass came just before it (the momentum pass run on its own).
void copy_state(Simulation& sim, const RowChunks& chunks, int c) {
  const Particles& p = sim.particles;
  double* const state = sim.reference.state.data();
  for (std::size_t i = chunks.begin(c); i < chunks.end(c); ++i) {
    state[4 * i] = p.x[i];
    state[4 * i + 1] = p.y[i];
    state[4 * i + 2] = p.vx[i];
    state[4 * i + 3] = p.vy[i];
  }
}

// The largest J2 of chunk c's particles and where (first particle on ties,
// as a scan finds it), for the run's peak stress without a scan of its own.
// J2 of a block into a buffer on the stack as one vector loop, then the
// block's maximum in order: a running maximum in the loop keeps it scalar.
void note_chunk_peak(Simulation& sim, const RowChunks& chunks, int c) {
  const Particles& p = sim.particles;
  const double *Sxx = p.sxx.data(), *Syy = p.syy.data(), *Szz = p.szz.data();
  const double* Sxy = p.sxy.data();
  constexpr std::size_t kBlock = 64;
  double j2_block[kBlock];
  double j2_max = 0.0;
  long peak = -1;
  for (std::size_t b0 = chunks.begin(c); b0 < chunks.end(c); b0 += kBlock) {
    const std::size_t b1 = std::min(chunks.end(c), b0 + kBlock);
#pragma omp simd
    for (std::size_t i = b0; i < b1; ++i) {
      const double dxx = Sxx[i], dyy = Syy[i], dzz = Szz[i], cxy = Sxy[i];
      j2_block[i - b0] = 0.5 * (dxx * dxx + dyy * dyy + dzz * dzz) + cxy * cxy;  // Particles::j2
    }
    for (std::size_t i = b0; i < b1; ++i) {
      if (j2_block[i - b0] > j2_max) {
        j2_max = j2_block[i - b0];
        peak = static_cast<long>(i);
      }
    }
  }
  sim.reference.chunk_peaks[c] = {j2_max, peak};
}

// The pair loop of the momentum equation, instantiated with and without
// hourglass control and the gathered mass: raw pointers, no branch. Each
// pair once, written to both ends (RowChunks):
//   stress share  a_i += -V0_j P_j G_ji / rho0_i,  a_j += -V0_i P_i G_ij / rho0_j
//   viscosity     a_i -= m_j Pi_ij g_ij,           a_j += m_i Pi_ij g_ij
// (equal and opposite: momentum is conserved exactly). The own share
// P_i sum_j V0_j G_ij needs no pair work (sgx, sgy). The row sums are left
// scalar on purpose: `omp simd` reductions over gathered neighbours cost more
// in gathers, masks and set-up than they save (docs/speed-accuracy-history.md).
// Momentum loop, pass 1 for chunk c; returns the energy the hourglass
// control removed per unit time (the viscosity's: accelerations_per_particle).
template <bool kHourglass, bool kUniform>
double momentum_pairs_of(Simulation& sim, RowChunks& chunks, int c) {
  const Particles& p = sim.particles;
  ReferencePairs& rp = sim.reference;
  const double mass_all = rp.uniform.mass;
  const double hg = sim.method.hourglass.coefficient;
  const std::uint32_t* rows = rp.rows.data();
  const std::uint32_t* jj = rp.j.data();
  const double* g = rp.g.data();  // G_ij, G_ji
  const double *visc_a = rp.visc_a.data(), *visc_b = rp.visc_b.data();
  const double* w0 = rp.w0.data();
  const double* e_over_rho0 = rp.e_over_rho0.data();
  const double* pv = rp.pv.data();        // V0 P: xx, xy, yx, yy
  const double* state = rp.state.data();  // x, y, vx, vy
  const double* vol0 = rp.vol0.data();
  const double* mass = p.mass.data();
  const double *x0 = p.x0.data(), *y0 = p.y0.data();
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
    const double* const si = state + 4 * i;
    const double xi = si[0], yi = si[1], vxi = si[2], vyi = si[3];
    const double mi = mass[i], vi = vol0[i];
    const double* const qi = pv + 4 * i;  // V0_i P_i
    const double qxx = qi[0], qxy = qi[1], qyx = qi[2], qyy = qi[3];
    // Row i continues the sums its pairs with j < i began.
    double sx = sums[4 * i], sy = sums[4 * i + 1], vsx = sums[4 * i + 2], vsy = sums[4 * i + 3];
    double hsx = kHourglass ? hg_sum[0][i] : 0.0, hsy = kHourglass ? hg_sum[1][i] : 0.0;
    // Inlined by force: out of line (GCC's choice with hourglass control) its
    // sums and array addresses go through the closure to memory at every
    // pair (docs/speed-accuracy-history.md, "Hourglass control's pair loop").
    auto pairs = [&](std::uint32_t k0, std::uint32_t k1, double* to, double* const* hg_to,
                     std::size_t base) __attribute__((always_inline)) {
      for (std::uint32_t k = k0; k < k1; ++k) {
        const std::uint32_t j = jj[k];
        const std::size_t t = j - base;
        const double* const gk = g + 4 * k;
        const double* const qj = pv + 4 * j;
        const double* const sj = state + 4 * j;
        const double bx = gk[2], by = gk[3];  // G_ji
        sx -= qj[0] * bx + qj[1] * by;        // V0_j P_j G_ji
        sy -= qj[2] * bx + qj[3] * by;
        const double ax = gk[0], ay = gk[1];  // G_ij
        const double share_x = -(qxx * ax + qxy * ay), share_y = -(qyx * ax + qyy * ay);
        const double dx = xi - sj[0], dy = yi - sj[1];
        const double dvx = vxi - sj[2], dvy = vyi - sj[3];
        const double vr = dvx * dx + dvy * dy;
        const double pg = viscosity_pair(visc_a[k], visc_b[k], vr);
        const double mj = kUniform ? mass_all : mass[j];
        vsx -= mj * pg * dx;
        vsy -= mj * pg * dy;
        // j's stress share and viscosity: += share * 1 and += (m_i pg) x_ij.
        const double mpg = mi * pg;
        add_product(to + 4 * t, Four{share_x, share_y, mpg, mpg}, Four{1.0, 1.0, dx, dy});
        if constexpr (kHourglass) {
          // Ganzenmueller 2015, eqs. (23)-(27) (hourglass.hpp); w0 holds
          // W / (2 |X|^2), e_over_rho0 E / rho0 (set-up).
          const double common = hourglass_stiffness(
              hg, w0[k], dx, dy, x0[i] - x0[j], y0[i] - y0[j], 0.5 * (Fxx[i] + Fxx[j]),
              0.5 * (Fxy[i] + Fxy[j]), 0.5 * (Fyx[i] + Fyx[j]), 0.5 * (Fyy[i] + Fyy[j]),
              dx * dx + dy * dy);
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
  }
  return dissipated;
}

template <bool kHourglass>
double momentum_pairs(Simulation& sim, RowChunks& chunks, int c) {
  return sim.reference.uniform.all ? momentum_pairs_of<kHourglass, true>(sim, chunks, c)
                                   : momentum_pairs_of<kHourglass, false>(sim, chunks, c);
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
  const double* pv = rp.pv.data();  // V0 P: xx, xy, yx, yy
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
    ax[i] = hx + inv_rho0 * (pv[4 * i] * sgx[i] + pv[4 * i + 1] * sgy[i] + sums[4 * i]);
    ay[i] = hy + inv_rho0 * (pv[4 * i + 2] * sgx[i] + pv[4 * i + 3] * sgy[i] + sums[4 * i + 1]);
    ax[i] += sums[4 * i + 2];
    ay[i] += sums[4 * i + 3];
    viscous -= mass[i] * (vx[i] * sums[4 * i + 2] + vy[i] * sums[4 * i + 3]);
  }
  return viscous;
}

// The passes of F and the stress, and those of the momentum equation, as
// lists for run_passes (core/passes.hpp): the stable-step estimate runs them
// apart, the step by terms together; the one-region step
// (integrate/integrator.cpp) interleaves them with the kicks and contact.
// Each pass sums the power it removes [W/m] (hourglass, viscosity).
template <bool kHourglass>
double run_stress_and_momentum(Simulation& sim, bool stress, bool momentum) {
  const Cuts cut = planned_chunks(sim);
  RowChunks &f_rows = cut.deformation, &m_rows = cut.momentum;
  auto displace = [&](int c, int, double&) { displacements(sim, f_rows.begin(c), f_rows.end(c)); };
  auto deformation = [&](int c, int, double&) { deformation_pairs(sim, f_rows, c); };
  auto stresses = [&](int c, int, double&) { stress_per_particle(sim, f_rows, c); };
  auto normals = [&](int c, int, double&) {
    turn_contact_normals(sim, f_rows.begin(c), f_rows.end(c));
  };
  auto peak = [&](int c, int, double&) { note_chunk_peak(sim, f_rows, c); };
  // The stress pass leaves the momentum pass's packed state; a momentum
  // pass on its own copies it first.
  auto state = [&](int c, int, double&) { copy_state(sim, f_rows, c); };
  auto momentum_sums = [&](int c, int, double& s) {
    s += momentum_pairs<kHourglass>(sim, m_rows, c);
  };
  auto accelerations = [&](int c, int, double& s) {
    s += accelerations_per_particle<kHourglass>(sim, m_rows, c);
  };
  const Pass<double> all[] = {
      {"displacements", Runs::OverChunks, &f_rows, displace, Sync::Barrier, stress},
      {"deformation gradient", Runs::OverChunks, &f_rows, deformation, Sync::Barrier, stress},
      {"stress", Runs::OverChunks, &f_rows, stresses, Sync::Barrier, stress},
      {"contact normals", Runs::OverChunks, &f_rows, normals, Sync::Continues, stress},
      {"peak stress", Runs::OverChunks, &f_rows, peak, Sync::Continues, stress},
      {"positions and velocities", Runs::OverChunks, &f_rows, state, Sync::Barrier,
       momentum && !stress},
      {"momentum sums", Runs::OverChunks, &m_rows, momentum_sums, Sync::Barrier, momentum},
      {"accelerations", Runs::OverChunks, &m_rows, accelerations, Sync::Barrier, momentum},
  };
  const double dissipated = run_passes<double>(all, f_rows.chunks(), kNeverStop);
  if (stress) gather_largest_j2(sim);
  return dissipated;
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
  run_stress_and_momentum<false>(sim, true, false);  // hourglass control acts in momentum only
}

void total_lagrangian_momentum(Simulation& sim, double dt) {
  const double dissipated = hourglass_ready(sim) ? run_stress_and_momentum<true>(sim, false, true)
                                                 : run_stress_and_momentum<false>(sim, false, true);
  sim.energy.dissipated += dt * dissipated;
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
  const Cuts cut = planned_chunks(sim);
  return {cut.deformation, cut.momentum, hourglass};
}

void displacements(Simulation& sim, std::size_t lo, std::size_t hi) {
  const Particles& p = sim.particles;
  const double *x = p.x.data(), *y = p.y.data(), *x0 = p.x0.data(), *y0 = p.y0.data();
  double* const u = sim.reference.u.data();
#pragma omp simd
  for (std::size_t i = lo; i < hi; ++i) {
    u[4 * i] = x[i] - x0[i];
    u[4 * i + 1] = y[i] - y0[i];
  }
}

void deformation_sums(Simulation& sim, TotalLagrangianPasses& tl, int c) {
  deformation_pairs(sim, tl.deformation, c);
}

void stress_from_deformation(Simulation& sim, TotalLagrangianPasses& tl, int c) {
  stress_per_particle(sim, tl.deformation, c);
}

void note_peak_stress(Simulation& sim, TotalLagrangianPasses& tl, int c) {
  note_chunk_peak(sim, tl.deformation, c);
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
  const double dissipated = hourglass_ready(sim) ? run_stress_and_momentum<true>(sim, true, true)
                                                 : run_stress_and_momentum<false>(sim, true, true);
  sim.energy.dissipated += dt * dissipated;
}

}  // namespace gearsph::physics
