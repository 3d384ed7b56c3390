#include "solver/physics/contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "solver/core/passes.hpp"
#include "solver/physics/contact_hertz.hpp"
#include "solver/physics/contact_law.hpp"
#include "solver/physics/contact_near_field.hpp"
#include "solver/physics/contact_seed_penalty.hpp"
#include "solver/physics/contact_smoothing.hpp"
#include "solver/physics/contact_surface.hpp"
#include "solver/physics/simulation.hpp"

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

// Most partners a particle has across a flat interface within r0 = dx on a
// square lattice (three: straight across and the two diagonals are at
// sqrt(2) dx, so within 1.5 dx at most 3 count).
constexpr double kPartnersAtOnce = 3.0;

}  // namespace

double contact_time_step_limit(const Simulation& sim) {
  const ContactConfig& config = sim.contact;
  if (!is_penalty(config.model) || sim.bodies.size() < 2) return 0.0;
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
  const double r0 = config.r0_over_dx * dx;
  double omega2 = 0.0;
  for (std::size_t a = 0; a < sim.bodies.size(); ++a) {
    for (std::size_t b = a + 1; b < sim.bodies.size(); ++b) {
      const Material &ma = sim.bodies[a].material, &mb = sim.bodies[b].material;
      const double e_star = contact_modulus(ma, mb);
      const double va = lightest(sim.bodies[a]), vb = lightest(sim.bodies[b]);
      const double vol = 2.0 * va * vb / (va + vb);
      // Stiffness at the deepest overlap we tolerate (r0/2) for Hertz; the
      // linear law has one stiffness, the near-field law a bound.
      const ContactLaw law = contact_law(config);
      const bool near = law == ContactLaw::NearField;
      double k = 0.0;
      switch (law) {
        case ContactLaw::Hertz:
          k = hertz_penalty(e_star, dx, 0.5 * r0).stiffness;
          break;
        case ContactLaw::NearField:
          k = kStiffSpring * e_star * vol / (dx * dx);
          break;
        case ContactLaw::Seed:
          k = seed_penalty(config.D, e_star, vol, r0, 0.0).stiffness;
          break;
      }
      const double inv_m = 1.0 / (ma.rho0 * va) + 1.0 / (mb.rho0 * vb);
      // The surface law's lateral hat weights add up to one over a row of
      // partners: one partner's stiffness at most (the near-field law's
      // tangent stiffness never exceeds its bound).
      omega2 = std::max(omega2, (near ? 1.0 : kPartnersAtOnce) * k * inv_m);
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

bool contact_smoothing(const Simulation& sim) {
  return sim.contact.model == ContactModel::Surface && sim.contact.smoothing_spacings > 0.0 &&
         sim.bodies.size() > 1;
}

namespace {

// How near a corner, in spacings, a particle keeps the tangent-line gap:
// beyond a spacing neither its hat nor its curvature's rate reaches the
// corner, and half a spacing more allows for graded rows (docs/contact.md,
// "The tip corner's zone").
constexpr double kCornerZone = 1.5;

// The smoothing tables of contact_smoothing.hpp from the reference
// configuration, once per run: a sweep over the surface particles sorted by x.
void build_smoothing(Simulation& sim) {
  const Particles& p = sim.particles;
  ContactState& st = sim.contact_state;
  const double reach = sim.contact.smoothing_spacings;
  std::vector<std::uint32_t> surface;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (std::isfinite(p.surf_depth[i])) surface.push_back(static_cast<std::uint32_t>(i));
  }
  std::sort(surface.begin(), surface.end(),
            [&](std::uint32_t a, std::uint32_t b) { return p.x0[a] < p.x0[b]; });
  auto spread_radius = [&](std::uint32_t i) {
    return reach * p.spacing[i] * sim.bodies[p.body[i]].contact_spread_scale;
  };
  double widest = 0.0;
  for (std::uint32_t i : surface) widest = std::max(widest, spread_radius(i));
  std::vector<std::vector<std::pair<std::uint32_t, double>>> rows(p.n);
  // Particles with a corner of their body's surface near them (curved_pair's
  // turning test, on any surface particle within kCornerZone of their
  // spacings, whatever its normal: a corner particle's normal is one
  // side's). A particle's hat reaches a spacing along the surface, and its
  // curvature's rate is taken over a spacing each side (scene/surfaces.cpp):
  // nearer a corner the surface would be drawn past the flank's end, where
  // it runs into the other body, or bent by the corner's turn. Neither is
  // the surface.
  st.smooth_surface.assign(p.n, 0);
  std::vector<std::uint8_t> near_corner(p.n, 0);
  for (std::size_t a = 0; a < surface.size(); ++a) {
    const std::uint32_t i = surface[a];
    const double radius = spread_radius(i);
    auto& row = rows[i];
    // Neighbours within `widest` in x on either side, then by distance.
    std::size_t lo = a;
    while (lo > 0 && p.x0[i] - p.x0[surface[lo - 1]] < widest) --lo;
    for (std::size_t b = lo; b < surface.size() && p.x0[surface[b]] - p.x0[i] < widest; ++b) {
      const std::uint32_t k = surface[b];
      if (p.body[k] != p.body[i]) continue;
      if (std::abs(p.surf_curvature[k]) * p.spacing[k] >= kCornerTurning &&
          std::hypot(p.x0[k] - p.x0[i], p.y0[k] - p.y0[i]) < kCornerZone * p.spacing[i]) {
        near_corner[i] = 1;
      }
      if (p.surf_nx[i] * p.surf_nx[k] + p.surf_ny[i] * p.surf_ny[k] < kSmoothingNormalCosine) {
        continue;
      }
      const double w = smoothing_weight(std::hypot(p.x0[k] - p.x0[i], p.y0[k] - p.y0[i]) / radius);
      if (w > 0.0) row.emplace_back(k, w);
    }
  }
  st.smooth_rows.assign(p.n + 1, 0);
  st.smooth_k.clear();
  st.smooth_w.clear();
  st.smooth_offset_x.assign(p.n, 0.0);
  st.smooth_offset_y.assign(p.n, 0.0);
  st.smooth_centre_x.assign(p.n, 0.0);
  st.smooth_centre_y.assign(p.n, 0.0);
  for (std::size_t i = 0; i < p.n; ++i) {
    double total = 0.0;
    for (const auto& [k, w] : rows[i]) total += w;
    double mx = 0.0, my = 0.0;
    for (const auto& [k, w] : rows[i]) {
      st.smooth_k.push_back(k);
      st.smooth_w.push_back(w / total);
      mx += w / total * p.x0[k];
      my += w / total * p.y0[k];
    }
    if (!rows[i].empty()) {
      st.smooth_offset_x[i] = p.x0[i] - mx;
      st.smooth_offset_y[i] = p.y0[i] - my;
      st.smooth_centre_x[i] = mx;
      st.smooth_centre_y[i] = my;
    }
    st.smooth_rows[i + 1] = static_cast<std::uint32_t>(st.smooth_k.size());
  }
  for (const std::uint32_t i : surface) st.smooth_surface[i] = near_corner[i] ? 0 : 1;
  st.spread_ax.assign(p.n, 0.0);
  st.spread_ay.assign(p.n, 0.0);
  st.smoothing_built = true;
}

// Lambda of every surface particle (contact_near_field.hpp): from its
// smoothing weights, or its own stretch of surface without smoothing.
void build_log_moments(Simulation& sim) {
  const Particles& p = sim.particles;
  ContactState& st = sim.contact_state;
  st.log_moment.assign(p.n, 0.0);
  const bool smooth = st.smoothing_built;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (!std::isfinite(p.surf_depth[i])) continue;
    if (!smooth || st.smooth_rows[i] == st.smooth_rows[i + 1]) {
      st.log_moment[i] = std::log(p.spacing[i]) - 1.5;
      continue;
    }
    double lambda = 0.0;
    for (std::uint32_t e = st.smooth_rows[i]; e < st.smooth_rows[i + 1]; ++e) {
      const std::uint32_t k = st.smooth_k[e];
      const double wk = st.smooth_w[e];
      for (std::uint32_t f = st.smooth_rows[i]; f < st.smooth_rows[i + 1]; ++f) {
        const std::uint32_t l = st.smooth_k[f];
        const double r = std::hypot(p.x0[k] - p.x0[l], p.y0[k] - p.y0[l]);
        lambda +=
            k == l ? wk * wk * (std::log(p.spacing[k]) - 1.5) : wk * st.smooth_w[f] * std::log(r);
      }
    }
    st.log_moment[i] = lambda;
  }
}

}  // namespace

SmoothedPoint smoothed_point(const Particles& p, const ContactState& st, std::size_t i) {
  SmoothedPoint s;
  // The receivers' rotation theta = atan2(S, C) from their reference
  // offsets A_k = X_k - sum W X (Procrustes): exact for a rigid motion, and
  // a function of the receivers' positions alone, so the spread force below
  // is the gradient of the gap it measures.
  double sdot = 0.0, cdot = 0.0;
  const double cx0 = st.smooth_centre_x[i], cy0 = st.smooth_centre_y[i];
  for (std::uint32_t e = st.smooth_rows[i]; e < st.smooth_rows[i + 1]; ++e) {
    const std::uint32_t k = st.smooth_k[e];
    const double w = st.smooth_w[e];
    const double ax = p.x0[k] - cx0, ay = p.y0[k] - cy0;
    s.x += w * p.x[k];
    s.y += w * p.y[k];
    s.vx += w * p.vx[k];
    s.vy += w * p.vy[k];
    s.c += w * (ax * p.x[k] + ay * p.y[k]);
    s.s += w * (ax * p.y[k] - ay * p.x[k]);
    cdot += w * (ax * p.vx[k] + ay * p.vy[k]);
    sdot += w * (ax * p.vy[k] - ay * p.vx[k]);
  }
  const double r2 = s.c * s.c + s.s * s.s;
  if (!(r2 > 0.0)) return s;  // a single receiver: no offset
  const double r = std::sqrt(r2), cos_t = s.c / r, sin_t = s.s / r;
  s.ox = cos_t * st.smooth_offset_x[i] - sin_t * st.smooth_offset_y[i];
  s.oy = sin_t * st.smooth_offset_x[i] + cos_t * st.smooth_offset_y[i];
  s.x += s.ox;
  s.y += s.oy;
  const double omega = (s.c * sdot - s.s * cdot) / r2;  // d theta / dt
  s.vx -= omega * s.oy;
  s.vy += omega * s.ox;
  return s;
}

void add_contact_accelerations(Simulation& sim, std::size_t lo, std::size_t hi) {
  Particles& p = sim.particles;
  if (!contact_smoothing(sim)) {
    for (std::size_t i = lo; i < hi; ++i) {
      p.ext_ax[i] += p.contact_ax[i];
      p.ext_ay[i] += p.contact_ay[i];
    }
    return;
  }
  // Only sources that touch have a force or a couple, and every source
  // that touches is a candidate (the others hold zeros, prepare_contact):
  // each thread walks the candidates in order and adds the share of its
  // own receivers. Per receiver the shares arrive in ascending source
  // order, as a table per receiver gave them (the same bits), at a few
  // touching sources a step instead of every receiver's table (4 % of the
  // gear's step; docs/speed-accuracy-history.md, twelfth round).
  ContactState& st = sim.contact_state;
  double* const fx = st.spread_ax.data();
  double* const fy = st.spread_ay.data();
  std::fill(fx + lo, fx + hi, 0.0);
  std::fill(fy + lo, fy + hi, 0.0);
  for (const std::uint32_t i : st.candidates) {
    if (p.contact_ax[i] == 0.0 && p.contact_ay[i] == 0.0 && st.couple_c[i] == 0.0 &&
        st.couple_s[i] == 0.0) {
      continue;
    }
    for (std::uint32_t e = st.smooth_rows[i]; e < st.smooth_rows[i + 1]; ++e) {
      const std::uint32_t k = st.smooth_k[e];
      if (k < lo || k >= hi) continue;
      const double w = st.smooth_w[e];
      // The share of the force, and of the couple M dtheta/dx_k =
      // w M (C z x A_k - S A_k) / (C^2 + S^2).
      const double ax = p.x0[k] - st.smooth_centre_x[i], ay = p.y0[k] - st.smooth_centre_y[i];
      fx[k] += w * (p.mass[i] * p.contact_ax[i] - st.couple_c[i] * ay - st.couple_s[i] * ax);
      fy[k] += w * (p.mass[i] * p.contact_ay[i] + st.couple_c[i] * ax - st.couple_s[i] * ay);
    }
  }
  for (std::size_t k = lo; k < hi; ++k) {
    p.ext_ax[k] += fx[k] / p.mass[k];
    p.ext_ay[k] += fy[k] / p.mass[k];
  }
}

void prepare_contact(Simulation& sim) {
  Particles& p = sim.particles;
  ContactState& state = sim.contact_state;
  const NeighbourList& nl = sim.contacts;
  if (sim.contact.model == ContactModel::Surface && state.log_moment.size() != p.n) {
    if (contact_smoothing(sim)) build_smoothing(sim);  // once per run
    build_log_moments(sim);
  }
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
  if (contact_smoothing(sim)) {
    state.couple_c.assign(p.n, 0.0);  // allocates at the first build only
    state.couple_s.assign(p.n, 0.0);
    state.smoothed.resize(p.n);
  }
  state.prepared_build = nl.builds();
}

// In 2D R = [[c, -s], [s, c]] with (c, s) along (F_xx + F_yy, F_yx - F_xy):
// a square root and a division, where an angle cost atan2, sin and cos. As a
// masked vector loop: a branch per particle mispredicted along the mesh
// zone, and left the thread holding it 2 us a step behind.
void turn_contact_normals(Simulation& sim, std::size_t lo, std::size_t hi) {
  Particles& p = sim.particles;
  ContactState& touch = sim.contact_state;
  // Contact candidates (penalty contact only), refreshed before this step's
  // forces, and their normals' scratch (sized when the list was built).
  if (sim.contacts.rows.size() != p.n + 1 || touch.normal_x.size() != p.n) return;
  const std::uint32_t* contact_rows = sim.contacts.rows.data();
  constexpr double kMaxDepth = std::numeric_limits<double>::max();
  const double *Fxx = p.fxx.data(), *Fxy = p.fxy.data(), *Fyx = p.fyx.data(), *Fyy = p.fyy.data();
  const double *nx0 = p.surf_nx.data(), *ny0 = p.surf_ny.data(), *surf_depth = p.surf_depth.data();
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

void turn_contact_normals_by_rot(Simulation& sim, std::size_t lo, std::size_t hi) {
  Particles& p = sim.particles;
  const NeighbourList& nl = sim.contacts;
  for (std::size_t i = lo; i < hi; ++i) {
    // Only particles with candidates need their normal (most have none).
    if (nl.rows[i] == nl.rows[i + 1] || !std::isfinite(p.surf_depth[i])) continue;
    turn_surface_normal(p, sim.contact_state, i, std::cos(p.rot[i]), std::sin(p.rot[i]));
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
  const std::size_t n = sim.particles.n;
  // Total-Lagrangian stress passes have turned the normals already.
  const bool turn = sim.contact.model == ContactModel::Surface &&
                    sim.method.formulation == Formulation::UpdatedLagrangian;
  auto normals = [&](int me, int team, ContactTally&) {
    const Share part = share(n, me, team);
    turn_contact_normals_by_rot(sim, part.lo, part.hi);
  };
  auto points = [&](int me, int team, ContactTally&) { smooth_contact_points(sim, me, team); };
  auto pairs = [&](int me, int team, ContactTally& t) { contact_pairs(sim, dt, me, team, t); };
  auto accelerations = [&](int me, int team, ContactTally&) {
    const Share part = share(n, me, team);
    add_contact_accelerations(sim, part.lo, part.hi);
  };
  const Pass<ContactTally> passes[] = {
      {"contact normals", Runs::OnEveryThread, nullptr, normals, Sync::Barrier, turn},
      {"contact smoothing", Runs::OnEveryThread, nullptr, points, Sync::Continues, true},
      {"contact pairs", Runs::OnEveryThread, nullptr, pairs, Sync::Barrier, true},
      {"contact forces", Runs::OnEveryThread, nullptr, accelerations, Sync::Barrier, true},
  };
  constexpr std::size_t kNeverStop = 0;
  record_contact(sim, run_passes<ContactTally>(passes, sim.threads, kNeverStop));
}

}  // namespace physics
}  // namespace gearsph
