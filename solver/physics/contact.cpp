#include "solver/physics/contact.hpp"

#include <algorithm>
#include <cmath>

#include "solver/core/simulation.hpp"
#include "solver/physics/contact_hertz.hpp"
#include "solver/physics/contact_seed_penalty.hpp"
#include "solver/physics/contact_surface.hpp"

namespace gearsph {

const char* contact_model_name(ContactModel m) {
  switch (m) {
    case ContactModel::SeedPenalty:
      return "seed_penalty";
    case ContactModel::Surface:
      return "surface_penalty";
    case ContactModel::Hertz:
      return "hertz";
    case ContactModel::Kernel:
      return "kernel";
    case ContactModel::None:
      break;
  }
  return "none";
}

namespace physics {

bool is_penalty(ContactModel m) {
  return m == ContactModel::SeedPenalty || m == ContactModel::Surface || m == ContactModel::Hertz;
}

namespace {

// Plane-strain contact modulus of two materials (Johnson 1985, eq. 4.23 form).
double contact_modulus(const Material& a, const Material& b) {
  return 1.0 / ((1.0 - a.nu * a.nu) / a.E + (1.0 - b.nu * b.nu) / b.E);
}

// Outline particles face each other when their normals are within 45
// degrees of opposed: cos(135 deg).
constexpr double kFacingCosine = 0.7071067811865476;

// Most partners a particle has across a flat interface within r0 = dx on a
// square lattice (three: straight across and the two diagonals are at
// sqrt(2) dx, so within 1.5 dx at most 3 count).
constexpr double kPartnersAtOnce = 3.0;

}  // namespace

double contact_time_step_limit(const Simulation& sim) {
  const ContactConfig& c = sim.contact;
  if (!is_penalty(c.model) || sim.bodies.size() < 2) return 0.0;
  // The stiffest pair: the finest spacing and the lightest particles of each
  // body (a lattice's dx and dx^2; body-fitted outline particles have about
  // half a cell).
  const Particles& p = sim.particles;
  auto lightest = [&](const Body& body) {
    double v = sim.discretization.dx * sim.discretization.dx;
    for (std::size_t i = body.begin; i < body.end; ++i) {
      if (p.spacing[i] != sim.discretization.dx) v = std::min(v, p.mass[i] / p.rho0[i]);
    }
    return v;
  };
  double dx = sim.discretization.dx;
  for (std::size_t i = 0; i < p.n; ++i) dx = std::min(dx, p.spacing[i]);
  const double r0 = c.r0_over_dx * dx;
  double omega2 = 0.0;
  for (std::size_t a = 0; a < sim.bodies.size(); ++a) {
    for (std::size_t b = a + 1; b < sim.bodies.size(); ++b) {
      const Material &ma = sim.bodies[a].material, &mb = sim.bodies[b].material;
      const double e_star = contact_modulus(ma, mb);
      const double va = lightest(sim.bodies[a]), vb = lightest(sim.bodies[b]);
      const double vol = 2.0 * va * vb / (va + vb);
      // Stiffness at the deepest overlap we tolerate (r0/2) for Hertz; the
      // linear law has one stiffness.
      const double k = c.model == ContactModel::Hertz
                           ? hertz_penalty(e_star, dx, 0.5 * r0).stiffness
                           : seed_penalty(c.D, e_star, vol, r0, 0.0).stiffness;
      const double inv_m = 1.0 / (ma.rho0 * va) + 1.0 / (mb.rho0 * vb);
      omega2 = std::max(omega2, kPartnersAtOnce * k * inv_m);
    }
  }
  return omega2 > 0.0 ? 2.0 / std::sqrt(omega2) : 0.0;
}

ContactTally& ContactTally::operator+=(const ContactTally& o) {
  active += o.active;
  stored += o.stored;
  dissipated += o.dissipated;
  deepest = std::max(deepest, o.deepest);
  for (int b = 0; b < kMaxBodies; ++b) {
    fx[b] += o.fx[b];
    fy[b] += o.fy[b];
  }
  return *this;
}

const std::uint8_t* contact_eligible(Simulation& sim) {
  if (sim.contact.model != ContactModel::Surface) return nullptr;
  const Particles& p = sim.particles;
  std::vector<std::uint8_t>& eligible = sim.contact_state.eligible;
  if (eligible.size() != p.n) {  // depths never change: once per run
    eligible.resize(p.n);
    for (std::size_t i = 0; i < p.n; ++i) eligible[i] = std::isfinite(p.surf_depth[i]) ? 1 : 0;
  }
  return eligible.data();
}

void prepare_contact(Simulation& sim) {
  Particles& p = sim.particles;
  ContactState& state = sim.contact_state;
  const NeighbourList& nl = sim.contacts;
  if (state.prepared_build == nl.builds()) return;
  if (sim.contact.model == ContactModel::Surface) {
    state.normal_x.resize(p.n);  // allocates once
    state.normal_y.resize(p.n);
  }
  state.candidates.clear();  // keeps its capacity
  for (std::size_t i = 0; i < p.n; ++i) {
    if (nl.rows[i] != nl.rows[i + 1]) state.candidates.push_back(static_cast<std::uint32_t>(i));
  }
  std::fill(p.contact_ax.begin(), p.contact_ax.end(), 0.0);
  std::fill(p.contact_ay.begin(), p.contact_ay.end(), 0.0);
  state.prepared_build = nl.builds();
}

void contact_pairs(Simulation& sim, double dt, ContactTally& tally) {
  Particles& p = sim.particles;
  const NeighbourList& nl = sim.contacts;
  const ContactConfig& c = sim.contact;
  const bool surface = c.model == ContactModel::Surface;
  const double* spacing = p.spacing.data();
  const double* normal_x = sim.contact_state.normal_x.data();
  const double* normal_y = sim.contact_state.normal_y.data();
  const std::uint32_t* candidates = sim.contact_state.candidates.data();
  const std::size_t count = sim.contact_state.candidates.size();
#pragma omp for schedule(static) nowait
  for (std::size_t a = 0; a < count; ++a) {
    const std::size_t i = candidates[a];
    const Material& mi = sim.material_of(i);
    const double vi = p.mass[i] / p.rho[i];
    double fx = 0.0, fy = 0.0;
    for (std::uint32_t k = nl.rows[i]; k < nl.rows[i + 1]; ++k) {
      const std::uint32_t j = nl.j[k];
      const double dxij = p.x[i] - p.x[j], dyij = p.y[i] - p.y[j];
      // The pair's spacing: the coarser of the two, so that the hat weight
      // of a fine particle spans its coarse partners' row (graded particles;
      // a lattice's dx otherwise). Symmetric in i and j.
      const double dx = std::max(spacing[i], spacing[j]), r0 = c.r0_over_dx * dx;
      double nx, ny, overlap, weight = 1.0;
      if (surface) {
        // True-surface gap (contact_surface.hpp); normals turned with the material.
        if (!std::isfinite(p.surf_depth[i]) || !std::isfinite(p.surf_depth[j])) continue;
        // Two particles on their outlines (body-fitted, depth 0) touch only
        // within a spacing of each other and with their outward normals
        // within 45 degrees of opposed: a rack's tip corner beside a pinion
        // flank passes the half-plane test of surface_pair from a spacing
        // away (normals 134 degrees apart), and pressed the teeth apart
        // where the neighbour's flank had 0.1 mm of play.
        if (p.surf_depth[i] == 0.0 && p.surf_depth[j] == 0.0 &&
            (dxij * dxij + dyij * dyij >= dx * dx ||
             normal_x[i] * normal_x[j] + normal_y[i] * normal_y[j] > -kFacingCosine)) {
          continue;
        }
        const SurfacePair sp = surface_pair(dxij, dyij, normal_x[i], normal_y[i], normal_x[j],
                                            normal_y[j], p.surf_depth[i], p.surf_depth[j], dx);
        if (!sp.active) continue;
        nx = sp.nx;
        ny = sp.ny;
        overlap = sp.overlap;
        weight = sp.weight;
      } else {
        const double r2 = dxij * dxij + dyij * dyij;
        if (r2 >= r0 * r0) continue;
        const double r = std::sqrt(r2);
        overlap = r0 - r;
        nx = dxij / r;
        ny = dyij / r;
      }
      const Material& mj = sim.material_of(j);
      const double e_star = contact_modulus(mi, mj);
      const double vj = p.mass[j] / p.rho[j];
      const double vol = 2.0 * vi * vj / (vi + vj);
      PairLaw law = c.model == ContactModel::Hertz
                        ? hertz_penalty(e_star, dx, overlap)
                        : seed_penalty(c.D, e_star, vol, surface ? dx : r0, overlap);
      law.force *= weight;
      law.stiffness *= weight;
      law.energy *= weight;
      // Dashpot on the normal approach speed, as a fraction of critical
      // damping of the pair oscillator; the total never pulls (no adhesion).
      const double vn = (p.vx[i] - p.vx[j]) * nx + (p.vy[i] - p.vy[j]) * ny;  // > 0 separating
      const double m_eff = p.mass[i] * p.mass[j] / (p.mass[i] + p.mass[j]);
      const double damper = 2.0 * c.damping_ratio * std::sqrt(law.stiffness * m_eff);
      const double f = std::max(0.0, law.force - damper * vn);
      fx += f * nx;
      fy += f * ny;
      // Each pair is seen from both ends: count its energy and the pair once.
      if (i < j) {
        ++tally.active;
        tally.stored += law.energy;
        tally.dissipated += (f - law.force) * -vn * dt;  // dashpot power times dt
      }
      tally.deepest = std::max(tally.deepest, overlap);
    }
    p.contact_ax[i] = fx / p.mass[i];
    p.contact_ay[i] = fy / p.mass[i];
    const int b = p.body[i];
    if (b < ContactTally::kMaxBodies) {
      tally.fx[b] += fx;
      tally.fy[b] += fy;
    }
  }
}

void record_contact(Simulation& sim, const ContactTally& tally) {
  ContactState& state = sim.contact_state;
  const std::size_t n_bodies = sim.bodies.size();
  state.force_x.assign(n_bodies, 0.0);  // allocates on the first step only
  state.force_y.assign(n_bodies, 0.0);
  for (std::size_t b = 0; b < n_bodies && b < static_cast<std::size_t>(ContactTally::kMaxBodies);
       ++b) {
    state.force_x[b] = tally.fx[b];
    state.force_y[b] = tally.fy[b];
  }
  state.active_pairs = tally.active;
  state.max_penetration = tally.deepest;
  state.stored_energy = tally.stored;
  sim.energy.dissipated += tally.dissipated;
}

void contact_forces(Simulation& sim, double dt) {
  if (!is_penalty(sim.contact.model)) {
    record_contact(sim, ContactTally{});
    return;
  }
  prepare_contact(sim);
  Particles& p = sim.particles;
  const NeighbourList& nl = sim.contacts;
  // Total-Lagrangian stress passes have turned the normals already.
  const bool turn = sim.contact.model == ContactModel::Surface &&
                    sim.method.formulation == Formulation::UpdatedLagrangian;
  const std::size_t n = p.n;
  ContactTally tally;
#pragma omp parallel num_threads(sim.threads) reduction(+ : tally)
  {
    if (turn) {
#pragma omp for schedule(static)
      for (std::size_t i = 0; i < n; ++i) {
        // Only particles with candidates need their normal (most have none).
        if (nl.rows[i] == nl.rows[i + 1] || !std::isfinite(p.surf_depth[i])) continue;
        turn_surface_normal(p, sim.contact_state, i, std::cos(p.rot[i]), std::sin(p.rot[i]));
      }
    }
    contact_pairs(sim, dt, tally);
    // The pair loop splits the candidates, this loop all particles.
#pragma omp barrier
#pragma omp for schedule(static) nowait
    for (std::size_t i = 0; i < n; ++i) {
      p.ext_ax[i] += p.contact_ax[i];
      p.ext_ay[i] += p.contact_ay[i];
    }
  }
  record_contact(sim, tally);
}

}  // namespace physics
}  // namespace gearsph
