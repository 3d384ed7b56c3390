// The total-Lagrangian step in one parallel region (integrate::step) against
// the same step with each term in a region of its own (step_by_terms), on a
// scene where every term of the region acts: stress, viscosity, surface
// contact with turned normals and a dashpot, a ramped load and mass damping
// (the quasi-static Hertz cylinder, pressed into its block from the start).
// The region also kicks and drifts the particles and, on one thread,
// rebuilds the contact list when its skin is used up.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/diagnostics/energy.hpp"
#include "solver/integrate/integrator.hpp"
#include "solver/integrate/motion.hpp"
#include "solver/job/job.hpp"
#include "solver/physics/contact.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph {
namespace {

using nlohmann::json;

constexpr int kSteps = 300;

Simulation pressed_cylinder(int threads) {
  const json job = {
      {"scene",
       {{"type", "hertz"},
        {"cap_height_over_a", 4},
        {"block_depth_over_a", 4},
        {"block_half_width_over_a", 4}}},
      {"method", {{"contact", {{"model", "surface_penalty"}, {"damping_ratio", 0.3}}}}}};
  PreparedJob prepared = prepare_job(job, threads);
  Simulation sim = prepared.scene.sim;
  sim.threads = threads;
  return sim;
}

template <class Step>
Simulation run(int threads, Step&& step) {
  Simulation sim = pressed_cylinder(threads);
  integrate::initialise(sim);
  for (int s = 0; s < kSteps; ++s) step(sim);
  return sim;
}

// Largest difference over the particles, relative to the largest value.
double relative_difference(const Column<double>& a, const Column<double>& b) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    diff = std::max(diff, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(a[i]));
  }
  return scale > 0.0 ? diff / scale : diff;
}

struct Field {
  const char* name;
  Column<double> Particles::*values;
};
const Field kFields[] = {{"x", &Particles::x},           {"vx", &Particles::vx},
                         {"vy", &Particles::vy},         {"sxx", &Particles::sxx},
                         {"sxy", &Particles::sxy},       {"p", &Particles::p},
                         {"ax", &Particles::ax},         {"ext_ax", &Particles::ext_ax},
                         {"ext_ay", &Particles::ext_ay}, {"contact_ay", &Particles::contact_ay}};

TEST(OneRegionStep, EveryTermActsInTheTestScene) {
  const Simulation sim = run(1, integrate::step);
  ASSERT_EQ(sim.method.formulation, Formulation::TotalLagrangian);
  EXPECT_GT(sim.contact_state.active_pairs, 0);
  EXPECT_GT(sim.damping_1_s, 0.0);
  EXPECT_GT(sim.energy.external_work, 0.0);
  EXPECT_GT(sim.energy.dissipated, 0.0);
}

// The meshing gear moves its contact surfaces by half the list's skin every
// few hundred steps: the region rebuilds the contact list on one thread,
// and the particles' values still match the separate regions' bit for bit.
TEST(OneRegionStep, RebuildsTheContactListLikeSeparateRegions) {
  auto gear = [](int threads, auto&& step) {
    PreparedJob prepared = prepare_job({{"scene", {{"type", "rack_pinion"}}}}, threads);
    Simulation sim = prepared.scene.sim;
    sim.threads = threads;
    integrate::initialise(sim);
    while (sim.contacts.builds() < 2 && sim.step < 20000) step(sim);
    return sim;
  };
  for (int threads : {1, 2}) {
    const Simulation a = gear(threads, integrate::step_by_terms);
    const Simulation b = gear(threads, integrate::step);
    ASSERT_FALSE(integrate::torque_driven(b)) << "this scene would not take the region's step";
    ASSERT_EQ(b.contacts.builds(), 2u) << "no rebuild in 20000 steps";
    ASSERT_EQ(a.step, b.step) << "the lists were rebuilt at different steps";
    for (const Field& f : kFields) {
      EXPECT_EQ(relative_difference(a.particles.*f.values, b.particles.*f.values), 0.0)
          << f.name << ", " << threads << " threads";
    }
  }
}

// The region runs the same passes over the same chunks of rows and the same
// split of the contact loop as the separate regions, so every particle's
// values come out bit for bit; only the step's totals (powers, dissipation)
// are summed in another order once there are several threads.
TEST(OneRegionStep, GivesTheSameBitsAsSeparateRegions) {
  for (int threads : {1, 2, 3}) {
    const Simulation a = run(threads, integrate::step_by_terms);
    const Simulation b = run(threads, integrate::step);
    for (const Field& f : kFields) {
      EXPECT_EQ(relative_difference(a.particles.*f.values, b.particles.*f.values), 0.0)
          << f.name << ", " << threads << " threads";
    }
    EXPECT_EQ(a.contact_state.force_y, b.contact_state.force_y) << threads << " threads";
    EXPECT_EQ(a.contact_state.stored_energy, b.contact_state.stored_energy);
    const double round_off = threads == 1 ? 0.0 : 1e-12;
    EXPECT_NEAR(a.energy.dissipated, b.energy.dissipated, round_off * a.energy.dissipated);
    EXPECT_NEAR(a.energy.external_work, b.energy.external_work, round_off * a.energy.external_work);
  }
}

// A particle thrown out of the domain stops the step inside the region: the
// force passes are skipped and the step names the particle, on any team.
TEST(OneRegionStep, AParticleLeavingTheDomainStopsTheStep) {
  for (int threads : {1, 2}) {
    Simulation sim = pressed_cylinder(threads);
    integrate::initialise(sim);
    for (int s = 0; s < 3; ++s) integrate::step(sim);
    const std::size_t lost = sim.particles.n / 2;
    sim.particles.vx[lost] = 10.0 * (sim.domain.x_max - sim.domain.x_min) / sim.dt;
    try {
      integrate::step(sim);
      ADD_FAILURE() << "the step went on, " << threads << " threads";
    } catch (const DivergenceError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("particle " + std::to_string(lost)), std::string::npos) << what;
      EXPECT_NE(what.find("left the domain"), std::string::npos) << what;
      EXPECT_NE(what.find("found by the pass 'domain check'"), std::string::npos) << what;
    }
    EXPECT_EQ(sim.step, 4);
  }
}

// Peak tracking takes the largest J2 that the stress pass found per chunk:
// the same particle and value as a scan over all particles, on any team.
TEST(OneRegionStep, TheStressPassFindsThePeakAScanFinds) {
  for (int threads : {1, 2, 3}) {
    Simulation sim = run(threads, integrate::step);
    ASSERT_EQ(sim.largest_j2.step, sim.step) << "the step's stress pass left no peak";
    const diagnostics::StressPeak found = diagnostics::max_von_mises(sim);
    sim.largest_j2.step = -1;  // forces the scan
    const diagnostics::StressPeak scanned = diagnostics::max_von_mises(sim);
    ASSERT_GE(scanned.particle, 0);
    EXPECT_EQ(found.particle, scanned.particle) << threads << " threads";
    EXPECT_EQ(found.von_mises, scanned.von_mises) << threads << " threads";
  }
}

// Every pass of the table is timed under its name on one step in
// PassTimes::kTimedEvery; a pass the scene does not have (the spins of
// torque-driven groups) is not.
TEST(OneRegionStep, TimesEveryPassOfTheTableByName) {
  const Simulation sim = run(2, integrate::step);
  const PassTimes& times = sim.pass_times;
  const std::int64_t timed = (kSteps + PassTimes::kTimedEvery - 1) / PassTimes::kTimedEvery;
  EXPECT_EQ(times.timed_steps(), timed);
  std::vector<std::string> names;
  for (const PassTime& t : times.entries()) {
    names.push_back(t.name);
    EXPECT_EQ(t.runs, timed) << t.name;
    EXPECT_GE(t.seconds, 0.0) << t.name;
  }
  auto timed_pass = [&](const char* name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  for (const char* expected :
       {"driven rotations", "kick and drift", "displacements", "domain check", "contact skin",
        "clock", "contact list", "deformation gradient", "stress", "contact normals", "peak stress",
        "contact pairs", "momentum sums", "accelerations", "external forces", "closing kick",
        "threads start and join"}) {
    EXPECT_TRUE(timed_pass(expected)) << expected;
  }
  // This scene's contact spreads no forces, and no group is torque-driven.
  ASSERT_FALSE(physics::contact_smoothing(sim));
  for (const char* absent :
       {"contact smoothing", "contact spread", "opening spin", "closing spin"}) {
    EXPECT_FALSE(timed_pass(absent)) << absent;
  }
  EXPECT_GT(times.total_seconds(), 0.0);
}

// The updated-Lagrangian table: the meshing gear on a lattice (one
// smoothing length) into its first contact, in one region a step and with
// each run of passes between barriers in a region of its own, the same
// bits on any team.
TEST(OneRegionStep, TheUpdatedLagrangianTableGivesTheSameBitsApart) {
  auto gear = [](int threads, auto&& step) {
    const json job = {{"scene", {{"type", "rack_pinion"}}},
                      {"discretization", {{"particles", "lattice"}}},
                      {"method", {{"formulation", "updated_lagrangian"}}}};
    PreparedJob prepared = prepare_job(job, threads);
    Simulation sim = prepared.scene.sim;
    sim.threads = threads;
    integrate::initialise(sim);
    while (sim.contact_state.active_pairs == 0 && sim.step < 5000) step(sim);
    for (int s = 0; s < 50; ++s) step(sim);
    return sim;
  };
  for (int threads : {1, 2}) {
    const Simulation a = gear(threads, integrate::step_by_terms);
    const Simulation b = gear(threads, integrate::step);
    ASSERT_EQ(b.method.formulation, Formulation::UpdatedLagrangian);
    ASSERT_GT(b.contact_state.active_pairs, 0) << "no contact in 5000 steps";
    ASSERT_EQ(a.step, b.step);
    for (const Field& f : kFields) {
      EXPECT_EQ(relative_difference(a.particles.*f.values, b.particles.*f.values), 0.0)
          << f.name << ", " << threads << " threads";
    }
    EXPECT_EQ(a.contact_state.force_x, b.contact_state.force_x) << threads << " threads";
  }
}

}  // namespace
}  // namespace gearsph
