// The fixed pairs of a total-Lagrangian run and their corrected gradients,
// built once (total_lagrangian.hpp).
#include <algorithm>
#include <cmath>
#include <type_traits>

#include "solver/core/setup_progress.hpp"
#include "solver/physics/artificial_viscosity.hpp"
#include "solver/physics/crack_cut.hpp"
#include "solver/physics/kernel_correction.hpp"
#include "solver/physics/simulation.hpp"
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
  // 8 bytes less (docs/speed-accuracy-history.md, memory per particle).
  ReferencePairs::Basis b{sim.particles.n, sim.discretization.kernel, sim.h(),
                          sim.method.correction, sim.method.hourglass.enabled()};
  // Graded particles: their smoothing lengths, summed, tell a changed
  // grading from the one the pairs were built for.
  const Particles& p = sim.particles;
  b.h_min = b.h_max = sim.discretization.h_over_dx * (p.n ? p.spacing[0] : 0.0);
  for (std::size_t i = 0; i < p.n; ++i) {
    const double hi = sim.discretization.h_over_dx * p.spacing[i];
    b.h_min = std::min(b.h_min, hi);
    b.h_max = std::max(b.h_max, hi);
    b.h_sum += hi;
  }
  if (p.n) b.h = b.h_min;  // the particles' own h (sim.h() for lattices)
  return b;
}

// Keeps the pairs within the support of their own smoothing length
// h_ij = (h_i + h_j) / 2, from a list built for the largest one.
void keep_pairs_within(const Particles& p, const Column<double>& h, double support,
                       std::vector<std::uint32_t>& rows, std::vector<std::uint32_t>& js) {
  std::size_t out = 0;
  std::uint32_t begin = rows[0];
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    const std::uint32_t end = rows[i + 1];
    for (std::uint32_t k = begin; k < end; ++k) {
      const std::uint32_t j = js[k];
      const double dx = p.x0[i] - p.x0[j], dy = p.y0[i] - p.y0[j];
      const double reach = support * 0.5 * (h[i] + h[j]);
      if (dx * dx + dy * dy < reach * reach) js[out++] = j;
    }
    begin = end;
    rows[i + 1] = static_cast<std::uint32_t>(out);
  }
  js.resize(out);
  js.shrink_to_fit();
}

// The pairs, their kernel values and corrected gradients. The per-particle
// arrays of the step come after (start_state): the corrections of every
// particle are held only until the gradients are built, and so not at the
// same time as those arrays (the set-up's peak of memory).
void build_pairs(Simulation& sim, const ReferencePairs::Basis& basis) {
  setup_progress("pairing particles", 0.0);
  Particles& p = sim.particles;
  ReferencePairs& rp = sim.reference;
  rp = ReferencePairs();  // what an earlier basis built, freed first
  // One smoothing length (lattices, even body-fitted particles), or one per
  // particle (graded): then a pair takes h_ij = (h_i + h_j) / 2.
  const bool graded = basis.h_min != basis.h_max;
  rp.hp.clear();
  if (graded) {
    rp.hp.resize(p.n);
    for (std::size_t i = 0; i < p.n; ++i) rp.hp[i] = sim.discretization.h_over_dx * p.spacing[i];
  }
  with_kernel(basis.kernel, graded ? basis.h_max : basis.h, [&](const auto& kernel) {
    using K = std::decay_t<decltype(kernel)>;
    {
      NeighbourList list;  // reference positions: each pair once, j > i
      list.build(p, kernel.radius, PairSelection::SameBody, /*reference=*/true, sim.threads);
      rp.rows = std::move(list.rows);
      rp.j = std::move(list.j);
    }
    if (graded) keep_pairs_within(p, rp.hp, K::shape_type::support, rp.rows, rp.j);
    std::vector<CutPair> cut;
    cut_pairs_across_cracks(p, sim.cracks, rp.rows, rp.j, &cut);  // its faces are free surfaces
    rp.faces = crack_face_pairs(sim, cut);                        // until they close
    auto h_of = [&](std::uint32_t i, std::uint32_t j) { return 0.5 * (rp.hp[i] + rp.hp[j]); };
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
          if (basis.keep_w) {
            rp.w0[k] = 0.5 * (graded ? K::W_at(r, h_of(i, j)) : kernel.W(r)) / (r * r);
          }
          rp.dw0[k] = graded ? K::dW_at(r, h_of(i, j)) : kernel.dW(r);
          mom[i].add(-rp.vol0[j] * rp.dw0[k] / r, dx, dy, quadratic);
          mom[j].add(-rp.vol0[i] * rp.dw0[k] / r, -dx, -dy, quadratic);
        }
      }
      for (std::size_t i = 0; i < n; ++i) {
        if (requested != GradientCorrection::None) {
          corr[i] = correction_from_moments(mom[i], requested, graded ? rp.hp[i] : basis.h);
        }
        p.correction_order[i] = static_cast<std::uint8_t>(corr[i].order);
      }
    }

    // G_ij = -w C_i phi(d) and G_ji = -w C_j phi(-d), d = X_i - X_j, and the
    // per-particle sums of V0_j G_ij (in the same ascending order).
    rp.g.assign(4 * m, 0.0);
    rp.sgx.assign(n, 0.0);
    rp.sgy.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::uint32_t k = rp.rows[i]; k < rp.rows[i + 1]; ++k) {
        const std::uint32_t j = rp.j[k];
        const double dx = p.x0[i] - p.x0[j], dy = p.y0[i] - p.y0[j];
        const double r = std::sqrt(dx * dx + dy * dy);
        const double dw_r = rp.dw0[k] / r;  // = -w
        double* const g = &rp.g[4 * k];     // G_ij, G_ji
        corrected_gradient(corr[i], dw_r, dx, dy, g[0], g[1]);
        corrected_gradient(corr[j], dw_r, -dx, -dy, g[2], g[3]);
        rp.sgx[i] += rp.vol0[j] * g[0];
        rp.sgy[i] += rp.vol0[j] * g[1];
        rp.sgx[j] += rp.vol0[i] * g[2];
        rp.sgy[j] += rp.vol0[i] * g[3];
      }
    }
    // Divided by V0_i: the step keeps P times the volume (ReferencePairs::pv).
    for (std::size_t i = 0; i < n; ++i) {
      rp.sgx[i] /= rp.vol0[i];
      rp.sgy[i] /= rp.vol0[i];
    }
  });
  rp.basis = basis;
}

// Each pair's artificial viscosity at the reference configuration
// (artificial_viscosity.hpp): from the method's constants and the
// materials, which a run may set after the pairs were built.
void reference_viscosities(Simulation& sim) {
  const Particles& p = sim.particles;
  ReferencePairs& rp = sim.reference;
  const ArtificialViscosity& av = sim.method.viscosity;
  rp.visc_a.assign(rp.pairs(), 0.0);
  rp.visc_b.assign(rp.pairs(), 0.0);
  for (std::size_t i = 0; i < p.n; ++i) {
    for (std::uint32_t k = rp.rows[i]; k < rp.rows[i + 1]; ++k) {
      const std::uint32_t j = rp.j[k];
      const double dx = p.x0[i] - p.x0[j], dy = p.y0[i] - p.y0[j];
      const double hij = rp.hp.empty() ? sim.h() : 0.5 * (rp.hp[i] + rp.hp[j]);
      const ReferenceViscosity v =
          reference_viscosity(av, rp.dw0[k], std::sqrt(dx * dx + dy * dy), hij,
                              0.5 * (p.cs[i] + p.cs[j]), 0.5 * (p.rho0[i] + p.rho0[j]));
      rp.visc_a[k] = v.a;
      rp.visc_b[k] = v.b;
    }
  }
}

// The per-particle state of the step as a fresh run starts it: zero sums,
// the viscosity's pair constants, chunks not yet cut.
void start_state(Simulation& sim) {
  ReferencePairs& rp = sim.reference;
  const std::size_t n = sim.particles.n;
  for (auto* v : {&rp.u, &rp.pv, &rp.state, &rp.sums}) v->assign(4 * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) rp.u[4 * i + 2] = rp.vol0[i];
  rp.e_over_rho0.assign(rp.basis.keep_w ? n : 0, 0.0);
  for (std::size_t i = 0; i < rp.e_over_rho0.size(); ++i) {
    rp.e_over_rho0[i] = sim.material_of(i).E / sim.particles.rho0[i];
  }
  rp.hg_ax.assign(rp.basis.keep_w ? n : 0, 0.0);
  rp.hg_ay.assign(rp.basis.keep_w ? n : 0, 0.0);
  const Particles& p = sim.particles;
  rp.uniform = {};
  if (n > 0) {
    bool all = true;
    for (std::size_t i = 0; i < n; ++i) all = all && p.mass[i] == p.mass[0];
    rp.uniform = {all, p.mass[0]};
  }
  reference_viscosities(sim);
  // Planned for these rows at the first pair loop.
  rp.deformation_chunks = RowChunks();
  rp.momentum_chunks = RowChunks();
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
