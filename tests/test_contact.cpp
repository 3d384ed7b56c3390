// Contact between bodies (physics/contact*.hpp): the pair laws, momentum
// conservation to round-off, no adhesion, and the diagnostics.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/diagnostics/energy.hpp"
#include "solver/integrate/integrator.hpp"
#include "solver/job/job.hpp"
#include "solver/physics/contact.hpp"
#include "solver/physics/contact_hertz.hpp"
#include "solver/physics/contact_near_field.hpp"
#include "solver/physics/contact_seed_penalty.hpp"
#include "solver/physics/contact_surface.hpp"
#include "solver/physics/simulation.hpp"
#include "solver/run/runner.hpp"
#include "tests/support/paper_static_check.hpp"

namespace gearsph {
namespace {

using nlohmann::json;

TEST(Contact, SeedPenaltyIsThePapersForceReadDimensionally) {
  // a_i = D (E*/rho) (r0 - r)/r0^2 for equal particles: F = m a = D E* V (r0 - r)/r0^2.
  const double D = 2.0, e_star = 1e11, dx = 1e-3, rho = 7800;
  const double volume = dx * dx, overlap = 1e-6;
  const physics::PairLaw law = physics::seed_penalty(D, e_star, volume, dx, overlap);
  const double accel = law.force / (rho * volume);
  EXPECT_NEAR(accel, D * e_star / rho * overlap / (dx * dx), 1e-9 * accel);
  EXPECT_DOUBLE_EQ(law.stiffness, D * e_star * volume / (dx * dx));
  EXPECT_DOUBLE_EQ(law.energy, 0.5 * law.stiffness * overlap * overlap);
}

TEST(Contact, HertzPenaltyStiffensWithOverlap) {
  const double e_star = 1e11, dx = 1e-3;
  const physics::PairLaw a = physics::hertz_penalty(e_star, dx, 1e-6);
  const physics::PairLaw b = physics::hertz_penalty(e_star, dx, 4e-6);
  EXPECT_NEAR(b.force / a.force, 8.0, 1e-12);  // delta^(3/2)
  EXPECT_NEAR(b.stiffness / a.stiffness, 2.0, 1e-12);
  // Energy is the integral of the force: 2/5 F delta.
  EXPECT_NEAR(b.energy, 0.4 * b.force * 4e-6, 1e-12 * b.energy);
}

// The near-field law (contact_near_field.hpp) against its derivation: the
// approach of a Hertz line contact minus that of the same load spread
// evenly over a stretch of length L, each computed by quadrature of the
// half-plane's surface displacement u(t) = -K int q(s) ln|t - s| ds
// (Johnson 1985, eq. 2.25b): at the Hertz centre, and averaged over the
// stretch. Steel on steel, 1 kN over 20 mm on an 8 mm flank against a flat.
TEST(Contact, NearFieldLawIsTheHertzApproachLessTheSpreadOnes) {
  const double E = 206e9, nu = 0.3, load = 5e4, radius = 8e-3, length = 5e-4;
  const double K = 2.0 * (1.0 - nu * nu) / (std::numbers::pi * E);
  const double e_star = 1.0 / (2.0 * (1.0 - nu * nu) / E);
  const double a = std::sqrt(4.0 * load * radius / (std::numbers::pi * e_star));
  const int n = 4000;
  // Hertz: p(s) = 2 F / (pi a^2) sqrt(a^2 - s^2); centre displacement.
  double hertz = 0.0;
  for (int k = 0; k < n; ++k) {
    const double th = std::numbers::pi * (k + 0.5) / n;  // s = a cos(th)
    const double s = a * std::cos(th);
    const double p = 2.0 * load / (std::numbers::pi * a * a) * a * std::sin(th);
    hertz += -K * p * std::log(std::abs(s)) * a * std::sin(th) * std::numbers::pi / n;
  }
  // Even spread over the stretch, averaged over it (midpoints, which never meet).
  double spread = 0.0;
  const int m = 1000;
  for (int k = 0; k < m; ++k) {
    for (int l = 0; l < m; ++l) {
      if (k == l) continue;
      spread += -K * load * std::log(std::abs(k - l) * length / m) / (double(m) * m);
    }
  }
  // The diagonal cells: the mean of ln|s - t| over a square of side L/m is ln(L/m) - 3/2.
  spread += -K * load * (std::log(length / m) - 1.5) / m;
  const double expected = 2.0 * (hertz - spread);  // both bodies, same material
  const double lambda = std::log(length) - 1.5;
  const physics::NearField nf =
      physics::near_field(e_star, K, K, lambda, lambda, 1.0 / radius, 1e30);
  const physics::PairLaw law = physics::near_field_law(nf, expected);
  EXPECT_NEAR(law.force, load, 2e-3 * load);
  EXPECT_GT(expected, 0.0);
}

// The law's own consistency: overlap(F) inverted, stiffness its slope,
// energy its integral, monotone, never pulling; a flat pair is the spring.
TEST(Contact, NearFieldLawIsMonotoneWithConsistentStiffnessAndEnergy) {
  const double e_star = 1.13e11, K = 2.0 / (std::numbers::pi * e_star);
  const physics::NearField nf =
      physics::near_field(e_star, 0.5 * K, 0.5 * K, -7.9, -7.7, 122.0, 3e11);
  double previous = 0.0;
  for (double d = 1e-9; d < 3e-5; d *= 1.7) {
    const physics::PairLaw law = physics::near_field_law(nf, d);
    ASSERT_GT(law.force, previous);
    previous = law.force;
    const double h = 1e-4 * d;
    const double slope =
        (physics::near_field_law(nf, d + h).force - physics::near_field_law(nf, d - h).force) /
        (2.0 * h);
    EXPECT_NEAR(law.stiffness, slope, 1e-4 * slope) << d;
    EXPECT_LE(law.stiffness, 3e11 * (1.0 + 1e-12));
    // Energy: trapezoidal integral of the force.
    double energy = 0.0;
    const int steps = 4000;
    for (int k = 0; k < steps; ++k) {
      const double f0 = physics::near_field_law(nf, d * k / steps).force;
      const double f1 = physics::near_field_law(nf, d * (k + 1) / steps).force;
      energy += 0.5 * (f0 + f1) * d / steps;
    }
    EXPECT_NEAR(law.energy, energy, 1e-4 * energy) << d;
  }
  EXPECT_EQ(physics::near_field_law(nf, -1e-6).force, 0.0);
  // Below F*, where the near field is softer than the spring, the overlap is
  // the continuum's approach alone: the spring adds no compliance there.
  const double f_star = physics::near_field_limit(nf);
  ASSERT_GT(f_star, 0.0);
  for (double f : {1e-3 * f_star, 0.1 * f_star, 0.9 * f_star}) {
    const double delta = nf.half_a * f * std::log(nf.f0 / f);
    EXPECT_NEAR(physics::near_field_law(nf, delta).force, f, 1e-9 * f);
  }
  const physics::NearField flat = physics::near_field(e_star, K, K, -7.9, -7.7, 0.0, 3e11);
  EXPECT_DOUBLE_EQ(physics::near_field_law(flat, 1e-6).force, 3e11 * 1e-6);
}

json bars(const std::string& model, const std::string& formulation) {
  return {{"scene", {{"type", "bar_impact"}, {"length_m", 0.02}, {"thickness_m", 0.004}}},
          {"discretization", {{"spacing_m", 0.0005}}},
          {"method", {{"formulation", formulation}, {"contact", {{"model", model}}}}}};
}

TEST(Contact, MomentumIsConservedToRoundOffThroughAnImpact) {
  // surface_penalty spreads each force over the surface around it
  // (contact_smoothing.hpp): the shares add up to the force.
  for (const char* model : {"seed_penalty", "hertz", "surface_penalty"}) {
    PreparedJob job = prepare_job(bars(model, "total_lagrangian"), 2);
    Simulation& sim = job.scene.sim;
    integrate::initialise(sim);
    const diagnostics::Momentum m0 = diagnostics::momentum(sim);
    double scale = 0.0;
    for (std::size_t i = 0; i < sim.particles.n; ++i) {
      scale += sim.particles.mass[i] * std::abs(sim.particles.vx[i]);
    }
    double max_pairs = 0;
    for (std::int64_t s = 0; s < job.steps; ++s) {
      integrate::step(sim);
      max_pairs = std::max(max_pairs, double(sim.contact_state.active_pairs));
      // Action and reaction: the two bars' contact forces cancel.
      EXPECT_NEAR(sim.contact_state.force_x[0] + sim.contact_state.force_x[1], 0.0,
                  1e-9 * (1.0 + std::abs(sim.contact_state.force_x[0])));
    }
    EXPECT_GT(max_pairs, 0) << model << ": the bars never touched";
    const diagnostics::Momentum m1 = diagnostics::momentum(sim);
    EXPECT_LT(std::abs(m1.px - m0.px), 1e-12 * scale) << model;
    EXPECT_LT(std::abs(m1.py - m0.py), 1e-12 * scale) << model;
  }
}

// The spread contact is the gradient of its penalty energy: through the
// bars' impact the energy balance stays flat at every smoothing radius.
// (When the offset of a smoothed point turned with its own particle while
// the couple turned with the receivers, a radius of 4-5 spacings added 30 %
// of the kinetic energy at the impact; the near field's spring at 10 E* V /
// dx^2 added 12 % through the time integration.)
TEST(Contact, SpreadContactKeepsTheEnergyThroughAnImpactAtAnyRadius) {
  for (double radius : {0.0, 2.0, 4.0, 6.0}) {
    json j = bars("surface_penalty", "total_lagrangian");
    j["method"]["contact"]["smoothing_spacings"] = radius;
    PreparedJob job = prepare_job(j, 2);
    const RunResult r = run_job(job);
    ASSERT_EQ(r.status, "completed") << r.message;
    const json& m = r.summary.at("health").at("measures");
    EXPECT_LT(m.at("energy_growth").get<double>(), 0.03) << "radius " << radius;
    EXPECT_TRUE(r.summary.at("analysis").at("separated").get<bool>()) << radius;
  }
}

TEST(Contact, PenaltyNeverPullsSoBarsSeparate) {
  for (const char* formulation : {"total_lagrangian", "updated_lagrangian"}) {
    PreparedJob job = prepare_job(bars("seed_penalty", formulation), 2);
    const RunResult r = run_job(job);
    ASSERT_EQ(r.status, "completed") << r.message;
    const json& a = r.summary.at("analysis");
    EXPECT_TRUE(a.at("separated").get<bool>()) << formulation;
    EXPECT_GT(a.at("restitution").get<double>(), 0.8) << formulation;
    // No pair force is ever attractive: the contact force on the left bar
    // always points left (or is zero).
    const auto f = r.history.column("contact_force_bar_left_N_per_m");
    for (double v : f) EXPECT_GE(v, 0.0);
  }
}

// Each surface particle's curvature (scene/surfaces.cpp), the near field's
// 1/R*: the Hertz cylinder's arc reads 1/R, the block's flat top 0.
TEST(Contact, SurfaceCurvatureIsTheOutlines) {
  const json job = {{"scene",
                     {{"type", "hertz"},
                      {"cap_height_over_a", 4},
                      {"block_depth_over_a", 4},
                      {"block_half_width_over_a", 4}}}};
  PreparedJob prepared = prepare_job(job, 1);
  const Particles& p = prepared.scene.sim.particles;
  const double R = prepared.job.at("scene").at("radius_m").get<double>();
  const double dx = prepared.scene.sim.discretization.dx;
  std::size_t arc = 0, flat = 0;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (!std::isfinite(p.surf_depth[i])) continue;
    if (p.body[i] == 0 && p.y0[i] < 2.0 * dx) {  // the arc near the contact
      EXPECT_NEAR(p.surf_curvature[i], 1.0 / R, 0.01 / R) << i;
      ++arc;
    }
    if (p.body[i] == 1 && p.y0[i] > -dx && std::abs(p.x0[i]) < 2.0 * dx) {
      EXPECT_NEAR(p.surf_curvature[i], 0.0, 1e-9 / R) << i;
      ++flat;
    }
  }
  EXPECT_GT(arc, 2u);
  EXPECT_GT(flat, 2u);
}

// A pair seen from its other end is the same pair with its normal flipped,
// and its force is the gradient of its energy: (n, dweight) are the
// overlap's and the weight's derivatives in x_i - x_j, by central
// differences of `at` (the pair at x_i - x_j moved by (ddx, ddy)), away from
// a hat's apex, where the weight has a kink. Returns the directions
// checked there.
template <class At>
int expect_consistent_pair(const physics::SurfacePair& sp, const physics::SurfacePair& back,
                           double overlap_scale, double h, At at) {
  EXPECT_NEAR(back.overlap, sp.overlap, 1e-12 * overlap_scale);
  EXPECT_NEAR(back.weight, sp.weight, 1e-12);
  EXPECT_NEAR(back.nx, -sp.nx, 1e-12);
  EXPECT_NEAR(back.ny, -sp.ny, 1e-12);
  const double eps = 1e-9;
  int smooth = 0;
  for (const auto& [ex, ey] : {std::pair{1.0, 0.0}, std::pair{0.0, 1.0}}) {
    const physics::SurfacePair plus = at(eps * ex, eps * ey), minus = at(-eps * ex, -eps * ey);
    if (!plus.active || !minus.active) continue;
    EXPECT_NEAR((plus.overlap - minus.overlap) / (2.0 * eps), -(sp.nx * ex + sp.ny * ey), 1e-5);
    const double up = (plus.weight - sp.weight) / eps, down = (sp.weight - minus.weight) / eps;
    if (std::abs(up - down) > 1e-2 / h) continue;
    ++smooth;
    EXPECT_NEAR(back.dweight * (back.tx * ex + back.ty * ey),
                -sp.dweight * (sp.tx * ex + sp.ty * ey), 1e-6 / h);
    EXPECT_NEAR(0.5 * (up + down), sp.dweight * (sp.tx * ex + sp.ty * ey), 1e-3 / h);
  }
  return smooth;
}

// The overlap of two curved outlines (contact_surface.hpp): rows of
// particles on a circle pressed into a line and into another circle, shifted
// along each other by any fraction of a spacing. Every pair around the
// contact reads the two surfaces' overlap, not the particles', with the
// common normal there, and the pairs' weights add up to one: the contact
// carries its load once, wherever it falls between particles. Swapping the
// pair flips the normal and nothing else.
TEST(Contact, CurvedOutlinesTouchOnceAtTheirOverlapWhereverTheContactFalls) {
  const double h_i = 0.5e-3, h_j = 0.7e-3, delta = 3e-6;
  // Body i: a circle of radius R_i above, centre (0, R_i - delta); body j
  // below, a circle of radius R_j (0 for a line) centred at (c, -R_j).
  for (const double r_j : {0.0, 20e-3}) {
    const double r_i = 8e-3, tilt = 0.2;
    // The two bodies touch along the direction `tilt` from the vertical:
    // the circles' centres lie on that line; overlap delta.
    const double ux = std::sin(tilt), uy = std::cos(tilt);
    const double ci_x = ux * (r_i - delta), ci_y = uy * (r_i - delta);
    const double cj_x = -ux * r_j, cj_y = -uy * r_j;
    const double kappa_i = 1.0 / r_i, kappa_j = r_j > 0.0 ? 1.0 / r_j : 0.0;
    for (const double shift : {0.0, 0.25, 0.5, 0.8}) {
      double total = 0.0;
      int smooth = 0;
      for (int a = -3; a <= 3; ++a) {
        // Particle a of body i at arc length (a + shift) h_i from the contact.
        const double phi_i = (a + shift) * h_i / r_i;
        const double ai = tilt + phi_i;  // direction of i's outward normal, reversed
        const double xi = ci_x - r_i * std::sin(ai), yi = ci_y - r_i * std::cos(ai);
        const double ni_x = -std::sin(ai), ni_y = -std::cos(ai);
        for (int b = -3; b <= 3; ++b) {
          const double s_j = (b - 0.3 * shift) * h_j;
          double xj, yj, nj_x, nj_y;
          if (r_j > 0.0) {
            const double aj = tilt + s_j / r_j;
            xj = cj_x + r_j * std::sin(aj);
            yj = cj_y + r_j * std::cos(aj);
            nj_x = std::sin(aj);
            nj_y = std::cos(aj);
          } else {
            xj = s_j * uy;
            yj = -s_j * ux;
            nj_x = ux;
            nj_y = uy;
          }
          const physics::SurfacePair sp = physics::curved_surface_pair(
              xi - xj, yi - yj, ni_x, ni_y, nj_x, nj_y, kappa_i, kappa_j, h_i, h_j);
          const physics::SurfacePair back = physics::curved_surface_pair(
              xj - xi, yj - yi, nj_x, nj_y, ni_x, ni_y, kappa_j, kappa_i, h_j, h_i);
          // (A particle a whole spacing from the contact has weight 0 either
          // way, to round-off.)
          EXPECT_NEAR(sp.active ? sp.weight : 0.0, back.active ? back.weight : 0.0, 1e-12);
          if (!sp.active || !back.active) continue;
          // The parabolas stand for the circles within a spacing or two:
          // the overlap to 2 % and the normal (the centres' line) to 1e-3.
          EXPECT_NEAR(sp.overlap, delta, 0.02 * delta) << r_j << " " << shift << " " << a << b;
          const double len = std::hypot(sp.nx, sp.ny);
          EXPECT_NEAR(sp.nx / len, ux, 1e-3);
          EXPECT_NEAR(sp.ny / len, uy, 1e-3);
          smooth += expect_consistent_pair(sp, back, delta, h_i, [&](double ddx, double ddy) {
            return physics::curved_surface_pair(xi - xj + ddx, yi - yj + ddy, ni_x, ni_y, nj_x,
                                                nj_y, kappa_i, kappa_j, h_i, h_j);
          });
          total += sp.weight;
        }
      }
      EXPECT_NEAR(total, 1.0, 0.01) << "R_j " << r_j << ", shift " << shift;
      EXPECT_GT(smooth, 2) << "R_j " << r_j << ", shift " << shift;
    }
  }
  EXPECT_TRUE(physics::curved_pair(1.0 / 8e-3, 0.0, h_i, h_j));
  EXPECT_FALSE(physics::curved_pair(0.0, 0.0, h_i, h_j));                  // the bars' faces
  EXPECT_FALSE(physics::curved_pair(1e-3, -1e-3, h_i, h_j));               // a convex in a concave
  EXPECT_FALSE(physics::curved_pair(1.0 / 8e-3, 1.0 / 0.5e-3, h_i, h_j));  // a rounded corner
}

// An involute against a flat, pressed in by delta at X (contact_surface.hpp,
// the cubic terms): rows of particles on the involute of a 22.55 mm base
// circle around its 8.2 mm radius of curvature (the paper's pitch point) and
// on the flat, shifted along each other by any fraction of a spacing. With
// each particle's curvature and its rate of change the pairs read the
// overlap at X to 1.2 % as their weights average it (each pair of weight
// over a quarter to 1 %); with the curvature alone (a parabola) to 8.4 %
// (34 %), the curvature changing by 8 % over a spacing.
// The overlap's gradient is the pair's force direction, as for circles.
TEST(Contact, CurvedPairsFollowAnInvolutesChangingCurvature) {
  const double rb = 22.55e-3, h_i = 0.6e-3, h_j = 0.9e-3, delta = 3e-6;
  // Involute of roll angle phi: P = rb (cos + phi sin, sin - phi cos), its
  // tangent (cos phi, sin phi), outward normal (sin phi, -cos phi) (the body
  // on its centre of curvature's side), radius of curvature rb phi, arc
  // length rb phi^2 / 2.
  const double phi_x = 8.2e-3 / rb, s_x = 0.5 * rb * phi_x * phi_x;
  const double px = rb * (std::cos(phi_x) + phi_x * std::sin(phi_x));
  const double py = rb * (std::sin(phi_x) - phi_x * std::cos(phi_x));
  const double nx = std::sin(phi_x), ny = -std::cos(phi_x);  // i's normal at X
  double worst_cubic = 0.0, worst_parabola = 0.0, worst_weighted_parabola = 0.0;
  int pairs = 0;
  for (const double shift : {0.0, 0.2, 0.45, 0.7, 0.9}) {
    double total = 0.0, cubic_error = 0.0, parabola_error = 0.0, parabola_total = 0.0;
    for (int a = -3; a <= 3; ++a) {
      const double s = s_x + (a + shift) * h_i;
      const double phi = std::sqrt(2.0 * s / rb);
      const double xi = rb * (std::cos(phi) + phi * std::sin(phi));
      const double yi = rb * (std::sin(phi) - phi * std::cos(phi));
      const double ni_x = std::sin(phi), ni_y = -std::cos(phi);
      // The particle's own tangent (-n_y, n_x) = (cos phi, sin phi) runs with
      // the arc length: d(kappa)/ds = -1 / (rb^2 phi^3).
      const double kappa_i = 1.0 / (rb * phi), rate_i = -1.0 / (rb * rb * phi * phi * phi);
      for (int b = -3; b <= 3; ++b) {
        // The flat's surface, delta into i, its outward normal -n.
        const double t = (b - 0.3 * shift) * h_j;
        const double xj = px - delta * nx - t * ny, yj = py - delta * ny + t * nx;
        const physics::SurfacePair cubic = physics::curved_surface_pair(
            xi - xj, yi - yj, ni_x, ni_y, -nx, -ny, kappa_i, 0.0, h_i, h_j, rate_i, 0.0);
        const physics::SurfacePair parabola = physics::curved_surface_pair(
            xi - xj, yi - yj, ni_x, ni_y, -nx, -ny, kappa_i, 0.0, h_i, h_j);
        const physics::SurfacePair back = physics::curved_surface_pair(
            xj - xi, yj - yi, -nx, -ny, ni_x, ni_y, 0.0, kappa_i, h_j, h_i, 0.0, rate_i);
        if (!cubic.active) continue;
        ++pairs;
        total += cubic.weight;
        cubic_error += cubic.weight * (cubic.overlap - delta);
        if (cubic.weight > 0.25) {
          worst_cubic = std::max(worst_cubic, std::abs(cubic.overlap - delta));
        }
        if (parabola.active) {
          parabola_error += parabola.weight * (parabola.overlap - delta);
          parabola_total += parabola.weight;
          if (parabola.weight > 0.25) {
            worst_parabola = std::max(worst_parabola, std::abs(parabola.overlap - delta));
          }
        }
        ASSERT_TRUE(back.active);
        expect_consistent_pair(cubic, back, delta, h_i, [&](double ddx, double ddy) {
          return physics::curved_surface_pair(xi - xj + ddx, yi - yj + ddy, ni_x, ni_y, -nx, -ny,
                                              kappa_i, 0.0, h_i, h_j, rate_i, 0.0);
        });
      }
    }
    std::printf("shift %.2f: weights %.4f, overlap error cubic %+.2f %%, parabola %+.2f %%\n",
                shift, total, 100.0 * cubic_error / total / delta,
                100.0 * parabola_error / parabola_total / delta);
    // (The two hats add up to one within 2.2 % along the involute's curve.)
    EXPECT_NEAR(total, 1.0, 0.03) << "shift " << shift;
    EXPECT_LT(std::abs(cubic_error / total), 0.02 * delta) << "shift " << shift;
    worst_weighted_parabola =
        std::max(worst_weighted_parabola, std::abs(parabola_error / parabola_total));
  }
  std::printf("worst pair of weight > 0.25: cubic %.3f um, parabola %.3f um\n", 1e6 * worst_cubic,
              1e6 * worst_parabola);
  EXPECT_GT(pairs, 10);
  EXPECT_LT(worst_cubic, 0.02 * delta);
  EXPECT_GT(worst_parabola, 0.1 * delta);
  EXPECT_GT(worst_weighted_parabola, 0.05 * delta);
}

// The paper's pinion's flanks as the contact sees them (scene/surfaces.cpp):
// each outline particle's surface (its normal, curvature and the
// curvature's rate), extended halfway to its neighbour, meets the
// neighbour's own within 0.1 um wherever the curvature changes by less than
// half between them: from the lowest contact (above the undercut, where the
// fillet cuts the involute at 11 degrees) to the tip. Taken from the chords'
// normals, with a curvature averaged across that kink, they were 1.1 um
// apart at the pitch point and 11 um beside the kink, against the contact's
// 1.4 um approach at 1 kN, and the load stuck to one particle. Nearer the
// base circle, where the curvature doubles over a spacing, they are up to
// 1.8 um apart (printed, not held).
TEST(Contact, FlankParticlesSurfacesMeetTheirNeighbours) {
  PreparedJob prepared = prepare_job(testing_support::paper_static_check("pitch"), 1);
  const Particles& p = prepared.scene.sim.particles;
  // The surface of particle k at t along its own tangent, and the height of
  // a point above particle k's surface.
  auto point = [&](std::size_t k, double t, double& x, double& y) {
    const double drop =
        0.5 * p.surf_curvature[k] * t * t + p.surf_curvature_rate[k] * t * t * t / 6.0;
    x = p.x0[k] - t * p.surf_ny[k] - drop * p.surf_nx[k];
    y = p.y0[k] + t * p.surf_nx[k] - drop * p.surf_ny[k];
  };
  auto height = [&](std::size_t k, double x, double y) {
    const double dx = x - p.x0[k], dy = y - p.y0[k];
    const double t = -dx * p.surf_ny[k] + dy * p.surf_nx[k];
    return dx * p.surf_nx[k] + dy * p.surf_ny[k] + 0.5 * p.surf_curvature[k] * t * t +
           p.surf_curvature_rate[k] * t * t * t / 6.0;
  };
  // Corners and the particles within 2.5 of their spacings of one keep the
  // tangent-line gap (contact.cpp, build_smoothing).
  std::vector<char> near_corner(p.n, 0);
  for (std::size_t c = 0; c < p.n; ++c) {
    if (p.surf_depth[c] != 0.0 || std::abs(p.surf_curvature[c]) * p.spacing[c] < 0.6) continue;
    for (std::size_t i = 0; i < p.n; ++i) {
      if (p.body[i] == p.body[c] &&
          std::hypot(p.x0[i] - p.x0[c], p.y0[i] - p.y0[c]) < 2.5 * p.spacing[i]) {
        near_corner[i] = 1;
      }
    }
  }
  int mid_flank = 0, low_flank = 0;
  double worst_mid = 0.0, worst_low = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.body[i] != 0 || p.surf_depth[i] != 0.0 || !(p.surf_curvature[i] > 0.0) ||
        near_corner[i]) {
      continue;
    }
    for (std::size_t j = 0; j < p.n; ++j) {
      if (j == i || p.body[j] != 0 || p.surf_depth[j] != 0.0 || !(p.surf_curvature[j] > 0.0) ||
          near_corner[j]) {
        continue;
      }
      const double dx = p.x0[j] - p.x0[i], dy = p.y0[j] - p.y0[i];
      const double d = std::hypot(dx, dy);
      const double along = -dx * p.surf_ny[i] + dy * p.surf_nx[i];
      // The next particle along i's tangent on the same smooth flank: a
      // spacing away, normals within 30 degrees, neither a corner.
      if (!(along > 0.0) || d > 1.3 * p.spacing[i] ||
          p.surf_nx[i] * p.surf_nx[j] + p.surf_ny[i] * p.surf_ny[j] < std::cos(0.5)) {
        continue;
      }
      // Where the curvature changes by less than half between them (the
      // flank from its lowest contact to the tip), and near the base circle,
      // where it doubles over a spacing.
      const double ratio = std::max(p.surf_curvature[j] / p.surf_curvature[i],
                                    p.surf_curvature[i] / p.surf_curvature[j]);
      const bool mid = ratio < 1.5;
      double x = 0.0, y = 0.0;
      point(i, 0.5 * along, x, y);
      const double miss = std::abs(height(j, x, y));
      (mid ? worst_mid : worst_low) = std::max(mid ? worst_mid : worst_low, miss);
      ++(mid ? mid_flank : low_flank);
    }
  }
  std::printf(
      "halfway between neighbours: %d pairs on the flank within %.3f um, %d by the base circle "
      "within %.3f um\n",
      mid_flank, 1e6 * worst_mid, low_flank, 1e6 * worst_low);
  EXPECT_LT(worst_mid, 0.15e-6);
  EXPECT_GT(mid_flank, 20);
}

// The curvature a Hertz contact meets (the near field's) leaves out a
// corner's turn: on the paper's pinion the tip corner turns by 54 degrees
// at one vertex, which averaged over a spacing read 23 times the
// involute's curvature there and made the tip's contact law follow the
// spacing (docs/contact.md).
TEST(Contact, HertzCurvatureLeavesOutACornersTurn) {
  PreparedJob prepared = prepare_job(testing_support::paper_static_check("tip"), 1);
  const Particles& p = prepared.scene.sim.particles;
  const double rb = 24e-3 * std::cos(20.0 * std::numbers::pi / 180.0), ra = 28e-3;
  double cx = 0.0, cy = 0.0;  // the pinion's centre: its hub's axis
  bool hub = false;
  for (const Motion& m : prepared.scene.sim.motions) {
    if (m.name != "pinion hub") continue;
    cx = m.cx;
    cy = m.cy;
    hub = true;
  }
  ASSERT_TRUE(hub);
  auto radius = [&](std::size_t i) { return std::hypot(p.x0[i] - cx, p.y0[i] - cy); };
  std::vector<std::size_t> tips;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.body[i] == 0 && p.surf_depth[i] == 0.0 &&
        std::abs(p.surf_curvature[i]) * p.spacing[i] >= 0.6 && std::abs(radius(i) - ra) < 1e-6) {
      tips.push_back(i);
    }
  }
  ASSERT_GE(tips.size(), 2u);
  int beside = 0;
  for (const std::size_t c : tips) {
    // The corner's own particle: between its two sides', the tip circle's
    // 1/r_a and the involute's 1/sqrt(r_a^2 - r_b^2) (its mean curvature
    // holds the corner's turn: 0.6 rad a spacing or more).
    EXPECT_GT(p.surf_hertz_curvature[c], 0.95 / ra) << c;
    EXPECT_LT(p.surf_hertz_curvature[c], 1.05 / std::sqrt(ra * ra - rb * rb)) << c;
    // Flank particles within a spacing of it: the involute's at their radius.
    for (std::size_t i = 0; i < p.n; ++i) {
      const double d = std::hypot(p.x0[i] - p.x0[c], p.y0[i] - p.y0[c]);
      const double r = radius(i);
      if (i == c || p.body[i] != 0 || p.surf_depth[i] != 0.0 || d >= p.spacing[i] ||
          r > ra - 1e-6) {
        continue;
      }
      ++beside;
      const double involute = 1.0 / std::sqrt(r * r - rb * rb);
      EXPECT_NEAR(p.surf_hertz_curvature[i], involute, 0.1 * involute) << i << " at r " << r;
    }
  }
  EXPECT_GE(beside, 2);
  // Away from corners and kinks the two are the same number.
  int away = 0;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.body[i] != 0 || p.surf_depth[i] != 0.0 || radius(i) < 23e-3 || radius(i) > 26e-3) {
      continue;
    }
    ++away;
    EXPECT_EQ(p.surf_hertz_curvature[i], p.surf_curvature[i]) << i;
  }
  EXPECT_GT(away, 10);
}

// A convex flank against a slightly concave one (a rack flank beside its
// root fillet): drawn apart step by step, a pair's overlap falls to zero
// and only then does the pair let go. The early rejection of pairs that are
// apart once ignored the concave parabola's sag inside its tangent line,
// and dropped pairs that still overlapped by a quarter of a micron, with
// their energy: a static check at coarse flanks gained energy until the
// health check stopped it.
TEST(Contact, CurvedPairLetsGoOnlyWhenItsOverlapDoes) {
  const double h_i = 0.72e-3, h_j = 0.93e-3;
  const double kappa_i = 75.0, kappa_j = -2.2;  // 1/m: an involute, a nearly straight flank
  int released = 0;
  for (const double tilt : {0.0, 0.02, -0.03}) {
    // j's normal along +y, i's opposed and tilted; i sits above j,
    // offset along the surface.
    const double ni_x = std::sin(tilt), ni_y = -std::cos(tilt);
    for (const double along : {0.2e-3, 0.5e-3, 0.8e-3}) {
      double last = -1.0;
      for (int k = 0; k < 4000; ++k) {
        const double gap = -2e-6 + 1e-9 * k;  // from 2 um of overlap to 2 um apart
        const physics::SurfacePair sp = physics::curved_surface_pair(
            along, gap, ni_x, ni_y, 0.0, 1.0, kappa_i, kappa_j, h_i, h_j);
        const double overlap = sp.active ? sp.overlap : 0.0;
        if (last > 0.0 && overlap == 0.0) {
          ++released;
          EXPECT_LT(last, 2e-9) << "tilt " << tilt << ", along " << along << ", gap " << gap;
        }
        last = overlap;
      }
    }
  }
  EXPECT_GE(released, 3);
}

// A corner's tangent-line pair (contact_surface.hpp, surface_pair) between
// outline particles starts where they come within dx of each other. A rack
// tip corner, its normal turned 60 degrees, meets a flank particle whose
// tangent line it already crosses by 35 um there: the pair's weight must be
// zero at that distance, so that its energy grows from nothing. The hat of
// the lateral offset was 0.06 there, and the paper's meshing case with a
// coarse rack corner stopped at 7.7 ms on the energy it made.
TEST(Contact, OutlinePairStartsWithNoWeightEvenWhereItsCornerAlreadyOverlaps) {
  const double dx = 1e-3, a = 25.0 * std::numbers::pi / 180, b = 60.0 * std::numbers::pi / 180;
  const double njx = -std::sin(a), njy = std::cos(a);  // the flank's normal
  const double nix = std::sin(b), niy = -std::cos(b);  // the corner's
  const double ex = 0.92 / std::hypot(0.92, 0.39), ey = 0.39 / std::hypot(0.92, 0.39);
  auto pair = [&](double r, bool on_outline) {
    return physics::surface_pair(r * ex, r * ey, nix, niy, njx, njy, 0.0, 0.0, dx, on_outline);
  };
  const physics::SurfacePair lateral = pair(0.999 * dx, false);
  ASSERT_TRUE(lateral.active);
  EXPECT_GT(lateral.overlap, 30e-6);
  EXPECT_GT(lateral.weight, 0.05);  // what made the energy jump
  for (const double r : {0.999 * dx, 0.99 * dx, 0.9 * dx, 0.5 * dx}) {
    const physics::SurfacePair sp = pair(r, true);
    ASSERT_TRUE(sp.active);
    EXPECT_NEAR(sp.weight, 1.0 - r / dx, 1e-12);
    // The weight's gradient, as the force uses it, against a central
    // difference in both directions.
    const double eps = 1e-9;
    for (const double angle : {0.0, 1.3}) {
      const double ux = std::cos(angle), uy = std::sin(angle);
      auto w_at = [&](double sgn) {
        return physics::surface_pair(r * ex + sgn * eps * ux, r * ey + sgn * eps * uy, nix, niy,
                                     njx, njy, 0.0, 0.0, dx, true)
            .weight;
      };
      const double fd = (w_at(1.0) - w_at(-1.0)) / (2.0 * eps);
      EXPECT_NEAR(sp.dweight * (sp.tx * ux + sp.ty * uy), fd, 1e-3 * std::abs(1.0 / dx));
    }
  }
  EXPECT_FALSE(pair(1.001 * dx, true).active);

  // Along a flat row of partners dx apart, touching by 1 um, the weights
  // still sum to one within the overlap over dx.
  for (const double shift : {0.0, 0.3, 0.77}) {
    double sum = 0.0;
    for (int k = -2; k <= 2; ++k) {
      const physics::SurfacePair sp =
          physics::surface_pair((k + shift) * dx, -1e-6, 0.0, -1.0, 0.0, 1.0, 0.0, 0.0, dx, true);
      if (sp.active) sum += sp.weight;
    }
    EXPECT_LE(std::abs(sum - 1.0), 1e-6 / dx + 1e-12) << "shift " << shift;
  }
}

// A convex corner (the pinion's tip) pressed on a flat flank: a point on a
// face, so the face's line measures the pair whatever the corner's own
// normal (one side's, tilted from the face's by a few degrees as the tooth
// bends). Its overlap is the corner's depth below the face's line, its
// force along the face's normal, and neither moves when the corner's normal
// turns (so the pair carries no couple through it). Measured from the
// larger gap, the corner's line took over as the tilt changed, and the tip's
// fillet peak per kilonewton rose 5.6 % between half the load and all of it.
TEST(Contact, CornerOnAFaceIsMeasuredFromTheFaceAlone) {
  const double dx = 0.7e-3, depth = 4e-6;
  const double njx = 0.0, njy = 1.0;  // the flank particle j at the origin
  for (const double tilt_deg : {-20.0, -3.0, 0.0, 3.0, 20.0}) {
    for (const double along : {-0.4 * dx, 0.1 * dx, 0.45 * dx}) {
      const double t = tilt_deg * std::numbers::pi / 180;
      const double nix = std::sin(t), niy = -std::cos(t);  // the corner's normal
      auto pair = [&](double nx, double ny, bool corner_i, bool corner_j) {
        return physics::surface_pair(along, -depth, nx, ny, njx, njy, 0.0, 0.0, dx, true, 0.0, 0.0,
                                     corner_i, corner_j);
      };
      const physics::SurfacePair sp = pair(nix, niy, true, false);
      ASSERT_TRUE(sp.active) << tilt_deg << " " << along;
      EXPECT_NEAR(sp.overlap, depth, 1e-15);
      EXPECT_NEAR(sp.nx, njx, 1e-15);
      EXPECT_NEAR(sp.ny, njy, 1e-15);
      const double turn = 1e-6;
      const physics::SurfacePair turned =
          pair(nix * std::cos(turn) - niy * std::sin(turn),
               nix * std::sin(turn) + niy * std::cos(turn), true, false);
      EXPECT_EQ(turned.overlap, sp.overlap);
      // Seen from the face's end (the corner as j), the same pair, mirrored.
      const physics::SurfacePair mirrored = physics::surface_pair(
          -along, depth, njx, njy, nix, niy, 0.0, 0.0, dx, true, 0.0, 0.0, false, true);
      ASSERT_TRUE(mirrored.active);
      EXPECT_NEAR(mirrored.overlap, depth, 1e-15);
      EXPECT_NEAR(mirrored.nx, -njx, 1e-15);
      EXPECT_NEAR(mirrored.ny, -njy, 1e-15);
      // Without the corner's rule the larger gap decides: the corner's own
      // line where the face's point lies on its open side (along and the
      // tilt of opposite signs), with another overlap.
      if (along * tilt_deg < 0.0 && std::abs(tilt_deg) >= 3.0 && std::abs(along) > 0.3 * dx) {
        EXPECT_GT(std::abs(pair(nix, niy, false, false).overlap - depth), 1e-7)
            << tilt_deg << " " << along;
      }
    }
  }
}

// A flank particle low on the pinion's flank (radius of curvature 2.5 mm)
// meets a rack tip corner passing in the backlash: the corner is 0.05 mm
// clear of the flank's true surface but 0.15 mm inside its tangent line,
// 1 mm along it. Measured from the flank's parabola the pair is apart;
// where they do overlap, the overlap's gradient is the force's direction.
TEST(Contact, TangentLinePairMeasuresFromAFlanksParabola) {
  const double dx = 1e-3, kappa = 1.0 / 2.5e-3;
  const double njx = 0.0, njy = 1.0;  // the flank particle j at the origin
  const double b = 50.0 * std::numbers::pi / 180;
  const double nix = std::sin(b), niy = -std::cos(b);  // the corner's normal
  auto pair = [&](double x, double y, double kj) {
    return physics::surface_pair(x, y, nix, niy, njx, njy, 0.0, 0.0, dx, true, 0.0, kj);
  };
  // The flank's surface at x is -kappa x^2 / 2: 0.2 mm below the line at 1 mm.
  const double x = 0.95e-3, clear = -0.5 * kappa * x * x + 0.05e-3;
  EXPECT_TRUE(pair(x, clear, 0.0).active);     // inside the tangent line
  EXPECT_FALSE(pair(x, clear, kappa).active);  // clear of the surface
  // 0.02 mm into the surface: an overlap of that much, less the slope's
  // second-order part, and its gradient.
  const double into = -0.5 * kappa * x * x - 0.02e-3;
  const physics::SurfacePair sp = pair(x, into, kappa);
  ASSERT_TRUE(sp.active);
  EXPECT_NEAR(sp.overlap, 0.02e-3, 1e-9);
  const double eps = 1e-10;
  const double dgx =
      (pair(x + eps, into, kappa).overlap - pair(x - eps, into, kappa).overlap) / (2.0 * eps);
  const double dgy =
      (pair(x, into + eps, kappa).overlap - pair(x, into - eps, kappa).overlap) / (2.0 * eps);
  EXPECT_NEAR(-dgx, sp.nx, 1e-5);
  EXPECT_NEAR(-dgy, sp.ny, 1e-5);
}

// The smoothing tables (contact_smoothing.hpp): each source's weights are a
// partition of unity over its own body's surface, the receivers' table is
// their transpose, and a smoothed point follows its particle through a
// rigid rotation and translation of the bodies.
TEST(Contact, SurfaceSmoothingIsAPartitionOfUnityThatFollowsRigidMotion) {
  PreparedJob job = prepare_job(bars("surface_penalty", "total_lagrangian"), 1);
  Simulation& sim = job.scene.sim;
  ASSERT_TRUE(physics::contact_smoothing(sim));
  physics::prepare_contact(sim);
  const ContactState& st = sim.contact_state;
  const Particles& p = sim.particles;
  ASSERT_TRUE(st.smoothing_built);
  std::size_t sources = 0;
  double weight_total = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (st.smooth_rows[i] == st.smooth_rows[i + 1]) {
      EXPECT_FALSE(std::isfinite(p.surf_depth[i])) << "surface particle " << i << " unsmoothed";
      continue;
    }
    ++sources;
    double sum = 0.0;
    std::size_t partners = 0;
    for (std::uint32_t e = st.smooth_rows[i]; e < st.smooth_rows[i + 1]; ++e) {
      const std::uint32_t k = st.smooth_k[e];
      EXPECT_EQ(p.body[k], p.body[i]);
      EXPECT_TRUE(std::isfinite(p.surf_depth[k]));
      sum += st.smooth_w[e];
      partners += k != i ? 1 : 0;
    }
    EXPECT_NEAR(sum, 1.0, 1e-14) << i;
    EXPECT_GE(partners, 2u) << i;  // a surface, not a single particle
    weight_total += sum;
  }
  ASSERT_GT(sources, 10u);
  EXPECT_NEAR(weight_total, static_cast<double>(sources), 1e-12 * weight_total);

  // Turn the bodies by 0.7 rad about a point and move them.
  Particles moved = p;
  const double c = std::cos(0.7), s = std::sin(0.7);
  for (std::size_t i = 0; i < p.n; ++i) {
    const double x = p.x0[i] - 0.003, y = p.y0[i] + 0.001;
    moved.x[i] = c * x - s * y + 0.02;
    moved.y[i] = s * x + c * y - 0.01;
    moved.vx[i] = 1.5;
    moved.vy[i] = -0.5;
  }
  for (std::size_t i = 0; i < p.n; ++i) {
    if (st.smooth_rows[i] == st.smooth_rows[i + 1]) continue;
    const SmoothedPoint q = physics::smoothed_point(moved, st, i);
    EXPECT_NEAR(q.x, moved.x[i], 1e-15) << i;
    EXPECT_NEAR(q.y, moved.y[i], 1e-15) << i;
    EXPECT_NEAR(q.vx, 1.5, 1e-13);
    EXPECT_NEAR(q.vy, -0.5, 1e-13);
  }
}

TEST(Contact, KernelCouplingSticks) {
  // The seed paper's motivation: bodies coupled through the kernel adhere.
  PreparedJob job = prepare_job(bars("kernel", "updated_lagrangian"), 2);
  const RunResult r = run_job(job);
  ASSERT_EQ(r.status, "completed") << r.message;
  const json& a = r.summary.at("analysis");
  EXPECT_FALSE(a.at("separated").get<bool>());
  EXPECT_LT(a.at("restitution").get<double>(), 0.3);
}

TEST(Contact, KernelCouplingNeedsUpdatedLagrangian) {
  try {
    prepare_job(bars("kernel", "total_lagrangian"), 1);
    FAIL() << "accepted";
  } catch (const InvalidJob& e) {
    ASSERT_EQ(e.issues.size(), 1u);
    EXPECT_EQ(e.issues[0].pointer, "/method/contact/model");
  }
}

TEST(Contact, StiffContactBoundsTheTimeStep) {
  json job = bars("seed_penalty", "total_lagrangian");
  job["method"]["contact"]["D"] = 500.0;
  const PreparedJob stiff = prepare_job(job, 1);
  EXPECT_EQ(stiff.time_step.limited_by, "contact stiffness");
  const PreparedJob soft = prepare_job(bars("seed_penalty", "total_lagrangian"), 1);
  EXPECT_LT(stiff.time_step.dt_limit, soft.time_step.dt_limit);
}

// The surface model's contact list holds only particles with a surface
// within reach (an interior particle's pairs were skipped each step), and
// the pair loop visits only particles with partners. The forces must be
// those of the full list, bit for bit, with every other particle's contact
// acceleration zero. The Hertz cylinder pressed into its block: pairs
// active from the first step.
TEST(Contact, SurfaceListOfSurfaceParticlesGivesTheFullListsForces) {
  const json job = {{"scene",
                     {{"type", "hertz"},
                      {"cap_height_over_a", 4},
                      {"block_depth_over_a", 4},
                      {"block_half_width_over_a", 4}}},
                    {"method", {{"contact", {{"model", "surface_penalty"}}}}}};
  PreparedJob prepared = prepare_job(job, 2);
  Simulation sim = prepared.scene.sim;
  integrate::initialise(sim);
  for (int s = 0; s < 300; ++s) integrate::step(sim);
  ASSERT_GT(sim.contact_state.active_pairs, 0);
  const Particles& p = sim.particles;
  const NeighbourList& list = sim.contacts;
  std::size_t interior = 0, candidates = 0;
  for (std::size_t i = 0; i < p.n; ++i) {
    const bool partners = list.rows[i] != list.rows[i + 1];
    if (!std::isfinite(p.surf_depth[i])) {
      ++interior;
      EXPECT_FALSE(partners) << "interior particle " << i << " in the contact list";
    }
    candidates += partners ? 1 : 0;
    if (!partners) {
      ASSERT_EQ(p.contact_ax[i], 0.0) << i;
      ASSERT_EQ(p.contact_ay[i], 0.0) << i;
    }
  }
  ASSERT_GT(interior, 0u);
  ASSERT_EQ(sim.contact_state.candidates.size(), candidates);

  // The same step's contact pass on the full list (every particle of the
  // other body within reach) and on every particle.
  Simulation full = sim;
  full.contacts.build(full.particles, sim.contacts.cutoff(), PairSelection::OtherBody,
                      /*reference=*/false, 1);
  full.contact_state.prepared_build = 0;
  physics::prepare_contact(full);
  ASSERT_GT(full.contacts.entries(), sim.contacts.entries());
  physics::ContactTally a, b;
  physics::contact_pairs(sim, sim.dt, a);
  physics::contact_pairs(full, sim.dt, b);
  ASSERT_GT(a.active, 0);
  EXPECT_EQ(a.active, b.active);
  EXPECT_EQ(a.stored, b.stored);
  for (std::size_t i = 0; i < p.n; ++i) {
    ASSERT_EQ(sim.particles.contact_ax[i], full.particles.contact_ax[i]) << i;
    ASSERT_EQ(sim.particles.contact_ay[i], full.particles.contact_ay[i]) << i;
  }
}

}  // namespace
}  // namespace gearsph

namespace gearsph {
namespace {

// A static check whose contact the particles resolve (scene
// resolve_contact): both flanks carry particles of an eighth of the Hertz
// half-width across the contact, graded back to the flanks' spacing away
// from it, and the contact load sits on single pairs. The pressure they
// give is the validation case gear_static/resolved_contact_pressure.
TEST(ResolvedContact, BothFlanksAreAnEighthOfTheHalfWidthAcrossTheContact) {
  const nlohmann::json job = {{"scene",
                               {{"type", "rack_pinion"},
                                {"quasi_static", true},
                                {"resolve_contact", true},
                                {"pinion", {{"omega_rad_s", 0.0}}},
                                {"rack", {{"velocity_m_s", 0.0}, {"load_N", 20000.0}}}}}};
  const PreparedJob prepared = prepare_job(job, 1);
  const nlohmann::json& rc = prepared.scene.description.at("resolved_contact");
  const double a = rc.at("hertz_half_width_estimate_m").get<double>();
  const double s = rc.at("contact_spacing_m").get<double>();
  EXPECT_DOUBLE_EQ(a / s, 8.0);
  // a = sqrt(4 F' R / (pi E*)) at the pitch point: F' = 20 kN / cos 20 deg
  // over 20 mm, R = sqrt(24^2 - 22.553^2) mm, E* = E / (2 (1 - nu^2)).
  const double r_curv = std::sqrt(0.024 * 0.024 - 0.0225526 * 0.0225526);
  const double e_star = 1.73e11 / (2.0 * (1.0 - 0.09));
  const double line_load = 20000.0 / std::cos(20.0 * std::numbers::pi / 180.0) / 0.02;
  EXPECT_NEAR(a, std::sqrt(4.0 * line_load * r_curv / (std::numbers::pi * e_star)), 1e-3 * a);
  EXPECT_EQ(prepared.scene.contact_smoothing_spacings, 0.0);

  const Simulation& sim = prepared.scene.sim;
  const Particles& p = sim.particles;
  const double cx = rc.at("point_m")[0].get<double>(), cy = rc.at("point_m")[1].get<double>();
  for (std::size_t b = 0; b < 2; ++b) {
    int across = 0;
    double far_spacing = 0.0;
    for (std::size_t i = sim.bodies[b].begin; i < sim.bodies[b].end; ++i) {
      const double d = std::hypot(p.x0[i] - cx, p.y0[i] - cy);
      if (d < a && std::isfinite(p.surf_depth[i])) {  // the flank's outline row
        ++across;
        EXPECT_LT(p.spacing[i], 1.1 * s) << sim.bodies[b].name << " particle " << i;
      }
      if (d > 3e-3 && d < 3.5e-3) far_spacing = std::max(far_spacing, p.spacing[i]);
    }
    // 2a of outline at a/8: 16 particles.
    EXPECT_GE(across, 15) << sim.bodies[b].name;
    EXPECT_GT(far_spacing, 5.0 * s) << sim.bodies[b].name << ": graded, not fine all over";
  }
}

}  // namespace
}  // namespace gearsph
