// The contact's two passes over the candidates (contact.hpp): the smoothed
// point of each candidate, then each candidate's pairs, the geometry of a
// pair (point or true surface) apart from its law and its force.
#include <algorithm>
#include <cmath>

#include "solver/core/passes.hpp"
#include "solver/physics/contact.hpp"
#include "solver/physics/contact_hertz.hpp"
#include "solver/physics/contact_law.hpp"
#include "solver/physics/contact_near_field.hpp"
#include "solver/physics/contact_seed_penalty.hpp"
#include "solver/physics/contact_smoothing.hpp"
#include "solver/physics/contact_surface.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph::physics {

namespace {

// The helpers of the pair loop are inlined by force (gnu::always_inline):
// called out of line, the compiler fuses other products into multiply-adds
// than in the loop written as one function, and the forces moved by
// round-off (1e-12 of the fillet stress); inlined, they are the same bits.

// The turn of a normal for the energy's derivative in it [rad].
constexpr double kTurn = 1e-6;

// Outline particles face each other when their normals are within 45
// degrees of opposed: cos(135 deg).
constexpr double kFacingCosine = 0.7071067811865476;

// Outline particle i's outward normal turned by its receivers' best-fit
// rotation (contact_smoothing.hpp), from its smoothed point's sums; without
// receivers to turn with, its reference normal.
void smoothed_normal(const Particles& p, const SmoothedPoint& s, std::size_t i, double& nx,
                     double& ny) {
  const double r = std::sqrt(s.c * s.c + s.s * s.s);
  const double c = r > 0.0 ? s.c / r : 1.0, sn = r > 0.0 ? s.s / r : 0.0;
  turn_normal(c, sn, p.surf_nx[i], p.surf_ny[i], nx, ny);
}

// What the pair loop reads, gathered once per pass.
struct PairContext {
  const Simulation& sim;
  const Particles& p;
  const ContactState& st;
  const ContactConfig& config;
  ContactLaw law;
  bool surface, smooth;
};

// One candidate i, as its pairs see it.
struct Candidate {
  std::size_t i;
  SmoothedPoint at;  // where i touches (contact_smoothing.hpp): its smoothed point, or itself
  double nx, ny;     // its normal turned by its receivers' rotation (smoothing only)
  double vol;        // its current volume
  const Material* mat;
};

SmoothedPoint where(const PairContext& c, std::size_t i) {
  const Particles& p = c.p;
  return c.smooth ? c.st.smoothed[i] : SmoothedPoint{p.x[i], p.y[i], p.vx[i], p.vy[i]};
}

// The geometry of a surface pair (contact_surface.hpp) seen from end a,
// with a's normal (ax, ay) and b's (bx, by), d = x_a - x_b.
struct SurfaceEnds {
  double sag_a, sag_b;  // a tangent-line pair's parabolas (0: none)
  bool outline, curved;
  bool corner_a, corner_b;  // convex corners (outline only): no tangent line
};
[[gnu::always_inline]] inline SurfacePair geometry_from(const Particles& p, std::size_t a,
                                                        std::size_t b, double dxab, double dyab,
                                                        double ax, double ay, double bx, double by,
                                                        double dx, const SurfaceEnds& e) {
  const double* spacing = p.spacing.data();
  return e.curved ? curved_surface_pair(dxab, dyab, ax, ay, bx, by, p.surf_curvature[a],
                                        p.surf_curvature[b], spacing[a], spacing[b],
                                        p.surf_curvature_rate[a], p.surf_curvature_rate[b])
                  : surface_pair(dxab, dyab, ax, ay, bx, by, p.surf_depth[a], p.surf_depth[b], dx,
                                 e.outline, e.sag_a, e.sag_b, e.corner_a, e.corner_b);
}

// The pair's geometry evaluated in one order for both ends (from the lower
// index), so that F_ji = -F_ij to the bit.
[[gnu::always_inline]] inline SurfacePair symmetric_geometry(const Particles& p, std::size_t i,
                                                             std::size_t j, double dxij,
                                                             double dyij, double nix, double niy,
                                                             double njx, double njy, double dx,
                                                             const SurfaceEnds& e) {
  if (i < j) return geometry_from(p, i, j, dxij, dyij, nix, niy, njx, njy, dx, e);
  const SurfaceEnds swapped{e.sag_b, e.sag_a, e.outline, e.curved, e.corner_b, e.corner_a};
  SurfacePair sp = geometry_from(p, j, i, -dxij, -dyij, njx, njy, nix, niy, dx, swapped);
  sp.nx = -sp.nx;
  sp.ny = -sp.ny;
  sp.tx = -sp.tx;
  sp.ty = -sp.ty;
  return sp;
}

// The surface pair (i, j), or an inactive one. With the smoothing also the
// geometry with i's normal turned by -+kTurn, for the energy's derivative
// in i's receivers' rotation.
[[gnu::always_inline]] inline SurfacePair surface_contact(const PairContext& c, const Candidate& ci,
                                                          std::size_t j, const SmoothedPoint& sj,
                                                          double dxij, double dyij, double dx,
                                                          SurfacePair turned[2]) {
  const Particles& p = c.p;
  const ContactState& st = c.st;
  const std::size_t i = ci.i;
  const double* spacing = p.spacing.data();
  const double *normal_x = st.normal_x.data(), *normal_y = st.normal_y.data();
  if (!std::isfinite(p.surf_depth[i]) || !std::isfinite(p.surf_depth[j])) return {};
  // Two particles on their outlines (body-fitted, depth 0) touch only within
  // a spacing of each other and with their outward normals within 45
  // degrees of opposed: a rack's tip corner beside a pinion flank passes the
  // half-plane test of surface_pair from a spacing away (normals 134 degrees
  // apart), and pressed the teeth apart where the neighbour's flank had
  // 0.1 mm of play.
  const bool outline = p.surf_depth[i] == 0.0 && p.surf_depth[j] == 0.0;
  // Smoothed (unresolved) contacts of curved outlines touch at one point
  // between the particles (contact_surface.hpp), whose hats reach a spacing
  // each way.
  const bool curved = outline && c.smooth && st.smooth_surface[i] && st.smooth_surface[j] &&
                      curved_pair(p.surf_curvature[i], p.surf_curvature[j], spacing[i], spacing[j]);
  const double apart = curved ? spacing[i] + spacing[j] : dx;
  if (outline && (dxij * dxij + dyij * dyij >= apart * apart ||
                  normal_x[i] * normal_x[j] + normal_y[i] * normal_y[j] > -kFacingCosine)) {
    return {};
  }
  // The normals: with the smoothing, turned by each particle's receivers'
  // rotation (its smoothed point's), a function of their positions, so that
  // the pair's energy has a gradient the smoothing's couple applies;
  // otherwise by the material's rotation.
  double nix = normal_x[i], niy = normal_y[i], njx = normal_x[j], njy = normal_y[j];
  if (c.smooth) {
    nix = ci.nx;
    niy = ci.ny;
    smoothed_normal(p, sj, j, njx, njy);
  }
  // A tangent-line pair measures from the parabola of a particle whose
  // surface is one (smoothed, away from corners), and a corner (turning by
  // kCornerTurning over its spacing) from its partner's line alone
  // (surface_pair).
  const SurfaceEnds e{outline && c.smooth && st.smooth_surface[i] ? p.surf_curvature[i] : 0.0,
                      outline && c.smooth && st.smooth_surface[j] ? p.surf_curvature[j] : 0.0,
                      outline,
                      curved,
                      outline && p.surf_curvature[i] * spacing[i] >= kCornerTurning,
                      outline && p.surf_curvature[j] * spacing[j] >= kCornerTurning};
  const SurfacePair sp = symmetric_geometry(p, i, j, dxij, dyij, nix, niy, njx, njy, dx, e);
  if (!sp.active || !c.smooth) return sp;
  // Seen from i, with i's normal turned by -+kTurn.
  for (int side = 0; side < 2; ++side) {
    const double turn = side ? kTurn : -kTurn, cs = std::cos(turn), sn = std::sin(turn);
    turned[side] = geometry_from(p, i, j, dxij, dyij, cs * nix - sn * niy, sn * nix + cs * niy, njx,
                                 njy, dx, e);
  }
  return sp;
}

// The pair of points i, j closer than r0 (the seed paper's and Hertz's
// laws), or an inactive one.
[[gnu::always_inline]] inline SurfacePair point_contact(double dxij, double dyij, double r0) {
  SurfacePair sp;
  const double r2 = dxij * dxij + dyij * dyij;
  if (r2 >= r0 * r0) return sp;
  const double r = std::sqrt(r2);
  sp.active = true;
  sp.overlap = r0 - r;
  sp.nx = dxij / r;
  sp.ny = dyij / r;
  sp.weight = 1.0;
  return sp;
}

// The pair's normal law at `overlap`: the one choice among the laws.
[[gnu::always_inline]] inline PairLaw normal_law(const PairContext& c, const NearField& nf,
                                                 double e_star, double vol, double dx, double r0,
                                                 double overlap) {
  switch (c.law) {
    case ContactLaw::Hertz:
      return hertz_penalty(e_star, dx, overlap);
    case ContactLaw::NearField:
      return near_field_law(nf, overlap);
    case ContactLaw::Seed:
      break;
  }
  return seed_penalty(c.config.D, e_star, vol, c.surface ? dx : r0, overlap);
}

// What one pair adds to its candidate i.
struct PairForce {
  double fx = 0.0, fy = 0.0;
  double energy_turn = 0.0;  // dE/dtheta_i through i's normal (smoothing)
};

// The force of the active pair (i, j) with geometry sp on i; its energy,
// dashpot and count into the tally (each pair once, from its lower index).
[[gnu::always_inline]] inline PairForce pair_force(const PairContext& c, const Candidate& ci,
                                                   std::size_t j, const SmoothedPoint& sj,
                                                   const SurfacePair& sp,
                                                   const SurfacePair turned[2], double dx,
                                                   double r0, double dt, ContactTally& tally) {
  const Particles& p = c.p;
  const std::size_t i = ci.i;
  const Material& mj = c.sim.material_of(j);
  const double e_star = contact_modulus(*ci.mat, mj);
  const double vj = p.mass[j] / p.rho[j];
  const double vol = 2.0 * ci.vol * vj / (ci.vol + vj);
  const NearField nf =
      c.law == ContactLaw::NearField
          ? near_field(e_star, plane_strain_compliance(*ci.mat), plane_strain_compliance(mj),
                       c.st.log_moment[i], c.st.log_moment[j],
                       p.surf_hertz_curvature[i] + p.surf_hertz_curvature[j],
                       kStiffSpring * e_star * vol / (dx * dx))
          : NearField{};
  const double overlap = sp.overlap;
  PairLaw law = normal_law(c, nf, e_star, vol, dx, r0, overlap);
  PairForce out;
  if (c.surface && c.smooth) {
    // The pair's energy w Phi depends on i's normal, which turns with i's
    // receivers: its derivative in that angle (a central difference of the
    // geometry, Phi linearised about the overlap) goes to the couple, so
    // that the contact's forces are the gradient of its energy also while
    // the bodies turn.
    auto energy = [&](const SurfacePair& q) {
      return q.active ? q.weight * (law.energy + law.force * (q.overlap - overlap)) : 0.0;
    };
    out.energy_turn = (energy(turned[1]) - energy(turned[0])) / (2.0 * kTurn);
  }
  const double phi = law.energy;  // before the weight, for its gradient below
  law.force *= sp.weight;
  law.stiffness *= sp.weight;
  law.energy *= sp.weight;
  // Dashpot on the normal approach speed, as a fraction of critical damping
  // of the pair oscillator; the total never pulls (no adhesion).
  const double vn = (ci.at.vx - sj.vx) * sp.nx + (ci.at.vy - sj.vy) * sp.ny;  // > 0 separating
  const double m_eff = p.mass[i] * p.mass[j] / (p.mass[i] + p.mass[j]);
  const double damper = 2.0 * c.config.damping_ratio * std::sqrt(law.stiffness * m_eff);
  const double f = std::max(0.0, law.force - damper * vn);
  // The weight's own gradient: the energy's tangential part as the partners
  // slide along each other (contact_surface.hpp).
  const double ft = -phi * sp.dweight;
  out.fx = f * sp.nx + ft * sp.tx;
  out.fy = f * sp.ny + ft * sp.ty;
  // Each pair is seen from both ends: count its energy and the pair once.
  if (i < j) {
    ++tally.active;
    tally.stored += law.energy;
    tally.dissipated += (f - law.force) * -vn * dt;  // dashpot power times dt
  }
  tally.deepest = std::max(tally.deepest, overlap);
  return out;
}

// Candidate i's pairs: its contact acceleration, the smoothing's couple
// and its body's share of the totals.
void candidate_contact(const PairContext& c, Simulation& sim, std::size_t i, double dt,
                       ContactTally& tally) {
  Particles& p = sim.particles;
  const NeighbourList& nl = sim.contacts;
  Candidate ci{i, where(c, i), 0.0, 0.0, p.mass[i] / p.rho[i], &sim.material_of(i)};
  // i's normal turned by its receivers' rotation, once for its pairs.
  if (c.surface && c.smooth && std::isfinite(p.surf_depth[i])) {
    smoothed_normal(p, ci.at, i, ci.nx, ci.ny);
  }
  double fx = 0.0, fy = 0.0, normal_moment = 0.0;
  for (std::uint32_t k = nl.rows[i]; k < nl.rows[i + 1]; ++k) {
    const std::uint32_t j = nl.j[k];
    const SmoothedPoint sj = where(c, j);
    const double dxij = ci.at.x - sj.x, dyij = ci.at.y - sj.y;
    // The pair's spacing: the coarser of the two, so that the hat weight of
    // a fine particle spans its coarse partners' row (graded particles; a
    // lattice's dx otherwise). Symmetric in i and j.
    const double dx = std::max(p.spacing[i], p.spacing[j]), r0 = c.config.r0_over_dx * dx;
    SurfacePair turned[2];
    const SurfacePair sp = c.surface ? surface_contact(c, ci, j, sj, dxij, dyij, dx, turned)
                                     : point_contact(dxij, dyij, r0);
    if (!sp.active) continue;
    const PairForce f = pair_force(c, ci, j, sj, sp, turned, dx, r0, dt, tally);
    fx += f.fx;
    fy += f.fy;
    normal_moment -= f.energy_turn;  // -dE/dtheta_i of i's surface pairs
  }
  p.contact_ax[i] = fx / p.mass[i];
  p.contact_ay[i] = fy / p.mass[i];
  if (c.smooth) {
    // The force acts at the smoothed point, the turned offset o away from
    // the receivers' weighted centroid; its moment o x f does work as the
    // receivers turn, and is spread as M dtheta/dx_k: with it the spread
    // force is the gradient of the penalty energy (contact_smoothing.hpp).
    const SmoothedPoint& si = ci.at;
    const double r2 = si.c * si.c + si.s * si.s;
    const double moment = r2 > 0.0 ? (si.ox * fy - si.oy * fx + normal_moment) / r2 : 0.0;
    sim.contact_state.couple_c[i] = moment * si.c;
    sim.contact_state.couple_s[i] = moment * si.s;
  }
  const int b = p.body[i];
  if (b < ContactTally::kMaxBodies) {
    tally.fx[b] += fx;
    tally.fy[b] += fy;
  }
}

PairContext context_of(const Simulation& sim) {
  const ContactConfig& config = sim.contact;
  return {sim,
          sim.particles,
          sim.contact_state,
          config,
          contact_law(config),
          config.model == ContactModel::Surface,
          contact_smoothing(sim)};
}

}  // namespace

void smooth_contact_points(Simulation& sim, int index, int of) {
  if (!contact_smoothing(sim)) return;
  const Particles& p = sim.particles;
  ContactState& st = sim.contact_state;
  const Share part = share(st.candidates.size(), index, of);
  for (std::size_t a = part.lo; a < part.hi; ++a) {
    const std::uint32_t i = st.candidates[a];
    st.smoothed[i] = smoothed_point(p, st, i);
  }
}

void contact_pairs(Simulation& sim, double dt, int index, int of, ContactTally& tally) {
  const PairContext c = context_of(sim);
  const std::vector<std::uint32_t>& candidates = sim.contact_state.candidates;
  const Share part = share(candidates.size(), index, of);
  for (std::size_t a = part.lo; a < part.hi; ++a)
    candidate_contact(c, sim, candidates[a], dt, tally);
}

void contact_pairs(Simulation& sim, double dt, ContactTally& tally) {
  smooth_contact_points(sim, 0, 1);
  contact_pairs(sim, dt, 0, 1, tally);
}

}  // namespace gearsph::physics
