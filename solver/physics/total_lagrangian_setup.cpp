// The fixed pairs of a total-Lagrangian run and their corrected gradients,
// built once (total_lagrangian.hpp).
#include <cmath>

#include "solver/core/simulation.hpp"
#include "solver/physics/kernel_correction.hpp"
#include "solver/physics/total_lagrangian.hpp"

namespace gearsph::physics {

namespace {

// G = w C phi(d) for one end of a pair (kernel_correction.hpp), w = W'(r)/r.
void corrected_gradient(const Correction& c, double w, double dx, double dy, double& gx,
                        double& gy) {
  const double q0 = dx * dx, q1 = dx * dy, q2 = dy * dy;
  gx = w * (c.lxx * dx + c.lxy * dy + c.qx[0] * q0 + c.qx[1] * q1 + c.qx[2] * q2);
  gy = w * (c.lyx * dx + c.lyy * dy + c.qy[0] * q0 + c.qy[1] * q1 + c.qy[2] * q2);
}

ReferencePairs::Basis basis_of(const Simulation& sim) {
  // W itself is needed only by hourglass control: without it a pair takes
  // 8 bytes less (docs/speed-accuracy.md, memory per particle).
  return {sim.particles.n, sim.discretization.kernel, sim.h(), sim.method.correction,
          sim.method.hourglass.enabled()};
}

// The pairs, their kernel values and corrected gradients. The per-particle
// arrays of the step come after (start_state): the corrections of every
// particle are held only until the gradients are built, and so not at the
// same time as those arrays (the set-up's peak of memory).
void build_pairs(Simulation& sim, const ReferencePairs::Basis& basis) {
  Particles& p = sim.particles;
  ReferencePairs& rp = sim.reference;
  rp = ReferencePairs();  // what an earlier basis built, freed first
  with_kernel(basis.kernel, basis.h, [&](const auto& kernel) {
    {
      NeighbourList list;  // reference positions: each pair once, j > i
      list.build(p, kernel.radius, PairSelection::SameBody, /*reference=*/true, sim.threads);
      rp.rows = std::move(list.rows);
      rp.j = std::move(list.j);
    }
    const std::size_t n = p.n, m = rp.pairs();
    rp.w0.assign(basis.keep_w ? m : 0, 0.0);
    rp.dw0.assign(m, 0.0);
    rp.vol0.resize(n);
    for (std::size_t i = 0; i < n; ++i) rp.vol0[i] = p.mass[i] / p.rho0[i];

    // Moment matrices of every particle from its reference neighbourhood. A
    // pair adds to both ends; particle i thus receives its neighbours in
    // ascending order (j < i from earlier rows, then its own row), as a
    // sorted full row would give them.
    const GradientCorrection requested = basis.correction;
    const bool quadratic = requested == GradientCorrection::Quadratic;
    std::vector<Correction> corr(n);
    {
      std::vector<Moments> mom(n);
      for (std::size_t i = 0; i < n; ++i) {
        for (std::uint32_t k = rp.rows[i]; k < rp.rows[i + 1]; ++k) {
          const std::uint32_t j = rp.j[k];
          const double dx = p.x0[i] - p.x0[j], dy = p.y0[i] - p.y0[j];
          const double r = std::sqrt(dx * dx + dy * dy);
          if (basis.keep_w) rp.w0[k] = kernel.W(r);
          rp.dw0[k] = kernel.dW(r);
          mom[i].add(-rp.vol0[j] * rp.dw0[k] / r, dx, dy, quadratic);
          mom[j].add(-rp.vol0[i] * rp.dw0[k] / r, -dx, -dy, quadratic);
        }
      }
      for (std::size_t i = 0; i < n; ++i) {
        if (requested != GradientCorrection::None) {
          corr[i] = correction_from_moments(mom[i], requested, basis.h);
        }
        p.correction_order[i] = static_cast<std::uint8_t>(corr[i].order);
      }
    }

    // G_ij = -w C_i phi(d) and G_ji = -w C_j phi(-d), d = X_i - X_j, and the
    // per-particle sums of V0_j G_ij (in the same ascending order).
    for (auto* v : {&rp.gix, &rp.giy, &rp.gjx, &rp.gjy}) v->assign(m, 0.0);
    rp.sgx.assign(n, 0.0);
    rp.sgy.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::uint32_t k = rp.rows[i]; k < rp.rows[i + 1]; ++k) {
        const std::uint32_t j = rp.j[k];
        const double dx = p.x0[i] - p.x0[j], dy = p.y0[i] - p.y0[j];
        const double r = std::sqrt(dx * dx + dy * dy);
        const double dw_r = rp.dw0[k] / r;  // = -w
        corrected_gradient(corr[i], dw_r, dx, dy, rp.gix[k], rp.giy[k]);
        corrected_gradient(corr[j], dw_r, -dx, -dy, rp.gjx[k], rp.gjy[k]);
        rp.sgx[i] += rp.vol0[j] * rp.gix[k];
        rp.sgy[i] += rp.vol0[j] * rp.giy[k];
        rp.sgx[j] += rp.vol0[i] * rp.gjx[k];
        rp.sgy[j] += rp.vol0[i] * rp.gjy[k];
      }
    }
    // Divided by V0_i: the step keeps P times the volume (ReferencePairs::px).
    for (std::size_t i = 0; i < n; ++i) {
      rp.sgx[i] /= rp.vol0[i];
      rp.sgy[i] /= rp.vol0[i];
    }
  });
  rp.basis = basis;
}

// The per-particle state of the step as a fresh run starts it: zero sums,
// no counts of approaching pairs, chunks not yet cut.
void start_state(Simulation& sim) {
  ReferencePairs& rp = sim.reference;
  const std::size_t n = sim.particles.n;
  for (auto* v : {&rp.px, &rp.py, &rp.pyx, &rp.pyy, &rp.ux, &rp.uy}) v->assign(n, 0.0);
  rp.sums.assign(4 * n, 0.0);
  rp.approaching.assign(n, 0);
  rp.hg_ax.assign(rp.basis.keep_w ? n : 0, 0.0);
  rp.hg_ay.assign(rp.basis.keep_w ? n : 0, 0.0);
  const Particles& p = sim.particles;
  rp.uniform = {};
  if (n > 0) {
    bool all = true;
    for (std::size_t i = 0; i < n; ++i) {
      all = all && p.mass[i] == p.mass[0] && p.cs[i] == p.cs[0];
    }
    rp.uniform = {all, p.mass[0], p.cs[0]};
  }
  // Planned for these rows at the first pair loop.
  rp.deformation_chunks = RowChunks();
  rp.momentum_chunks = RowChunks();
  rp.planned_step = -1;
  rp.chunk_peaks.clear();
  rp.lambda_body.clear();
  rp.mu_body.clear();
  for (const Body& b : sim.bodies) {
    rp.lambda_body.push_back(b.material.lame_lambda());
    rp.mu_body.push_back(b.material.shear_modulus());
  }
}

}  // namespace

void total_lagrangian_setup(Simulation& sim) {
  const ReferencePairs::Basis basis = basis_of(sim);
  if (!sim.reference.built() || !(sim.reference.basis == basis)) build_pairs(sim, basis);
  start_state(sim);
}

}  // namespace gearsph::physics
