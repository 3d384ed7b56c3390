// Contact between bodies (physics/contact*.hpp): the pair laws, momentum
// conservation to round-off, no adhesion, and the diagnostics.
#include <gtest/gtest.h>

#include <cmath>

#include "solver/core/simulation.hpp"
#include "solver/diagnostics/energy.hpp"
#include "solver/integrate/integrator.hpp"
#include "solver/job/job.hpp"
#include "solver/physics/contact.hpp"
#include "solver/physics/contact_hertz.hpp"
#include "solver/physics/contact_seed_penalty.hpp"
#include "solver/run/runner.hpp"

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

json bars(const std::string& model, const std::string& formulation) {
  return {{"scene", {{"type", "bar_impact"}, {"length_m", 0.02}, {"thickness_m", 0.004}}},
          {"discretization", {{"spacing_m", 0.0005}}},
          {"method", {{"formulation", formulation}, {"contact", {{"model", model}}}}}};
}

TEST(Contact, MomentumIsConservedToRoundOffThroughAnImpact) {
  for (const char* model : {"seed_penalty", "hertz"}) {
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

TEST(Contact, KernelCouplingSticks) {
  // The paper's motivation: bodies coupled through the kernel adhere.
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
