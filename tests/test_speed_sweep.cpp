// The speed sweep's request and plan (solver/study/speed_sweep.hpp) and the
// masses the lumped model takes from the scene: refusals at their JSON
// pointers before any job runs, the speeds' jobs at the ratios asked for,
// the plan kept as a document, the steady mesh that ends each speed's run,
// and rack.attached_mass_kg on the rack's guided back.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "solver/job/job.hpp"
#include "solver/scene/rack_pinion.hpp"
#include "solver/study/speed_sweep.hpp"

namespace gearsph::study {
namespace {

using json = nlohmann::json;

// The paper's pair at 5 kN on a coarse lattice: a scene built in a second.
json loaded_job() {
  return {{"name", "sweep-test"},
          {"scene",
           {{"type", "rack_pinion"},
            {"pinion", {{"omega_rad_s", -15.0}}},
            {"rack", {{"velocity_m_s", -0.36}, {"load_N", 5000.0}}}}},
          {"discretization", {{"particles", "lattice"}, {"spacing_mm", 2.0}}}};
}

std::vector<std::string> pointers_of(const json& request) {
  try {
    read_speed_sweep(request);
  } catch (const InvalidJob& e) {
    std::vector<std::string> out;
    for (const JobIssue& i : e.issues) {
      EXPECT_FALSE(i.message.empty()) << i.pointer;
      out.push_back(i.pointer);
    }
    return out;
  }
  return {};
}

TEST(SpeedSweep, RefusesBadRequestsAtTheirPointers) {
  EXPECT_TRUE(pointers_of({{"job", loaded_job()}, {"ratios", {0.5, 1.0}}}).empty());
  EXPECT_EQ(pointers_of({{"job", loaded_job()}, {"ratios", {0.5, -1.0, 0.0}}}),
            (std::vector<std::string>{"/ratios/1", "/ratios/2"}));
  EXPECT_EQ(pointers_of({{"job", loaded_job()}, {"ratios", {0.5, "fast"}}}),
            std::vector<std::string>{"/ratios/1"});
  EXPECT_EQ(pointers_of({{"job", loaded_job()}, {"ratios", json::array()}}),
            std::vector<std::string>{"/ratios"});
  json unloaded = loaded_job();
  unloaded["scene"]["rack"]["load_N"] = 0.0;
  EXPECT_EQ(pointers_of({{"job", unloaded}}), std::vector<std::string>{"/job/scene/rack/load_N"});
  json still = loaded_job();
  still["scene"]["quasi_static"] = true;
  EXPECT_EQ(pointers_of({{"job", still}}), std::vector<std::string>{"/job/scene/quasi_static"});
  json plate = {{"scene", {{"type", "plate"}}}};
  EXPECT_EQ(pointers_of({{"job", plate}}), std::vector<std::string>{"/job/scene/type"});
  // The job's own refusals, under /job.
  json typo = loaded_job();
  typo["scene"]["rack"]["attached_mass_kg"] = -1.0;
  EXPECT_EQ(pointers_of({{"job", typo}}),
            std::vector<std::string>{"/job/scene/rack/attached_mass_kg"});
  EXPECT_EQ(pointers_of({{"ratios", {1.0}}}), std::vector<std::string>{"/job"});
  EXPECT_EQ(pointers_of({{"job", loaded_job()}, {"stiffness", "fe"}}),
            std::vector<std::string>{"/stiffness"});
  EXPECT_EQ(pointers_of({{"job", loaded_job()}, {"stiffness_positions", 1}}),
            std::vector<std::string>{"/stiffness_positions"});
}

TEST(SpeedSweep, PlansEachSpeedAtItsRatioAndRefusesJobsOverTheLimits) {
  const SpeedSweepRequest req = read_speed_sweep(
      {{"job", loaded_job()}, {"ratios", {0.5, 1.0}}, {"steady_periods", 2}, {"stiffness", "iso"}});
  const SpeedSweepPlan plan = plan_speed_sweep(req, SweepLimits{});
  ASSERT_EQ(plan.jobs.size(), 2u);
  const double f_n = plan.natural_frequency_Hz;
  EXPECT_GT(f_n, 0.0);
  for (std::size_t k = 0; k < 2; ++k) {
    const json& s = plan.jobs[k].at("scene");
    const double omega = s.at("pinion").at("omega_rad_s").get<double>();
    // f_mesh = |omega| z / (2 pi), the rack at the pitch line's speed.
    EXPECT_NEAR(std::abs(omega) * 12 / (2 * std::numbers::pi), req.ratios[k] * f_n, 1e-9 * f_n);
    EXPECT_LT(omega, 0.0);  // the job's sense of rotation
    EXPECT_NEAR(s.at("rack").at("velocity_m_s").get<double>(), omega * 0.024, 1e-12);
    EXPECT_EQ(s.at("pinion").at("modelled_teeth"), "all");
    // Each speed ends once its mesh has been steady for the periods asked.
    EXPECT_EQ(s.at("steady_mesh_periods"), 2);
  }
  // Every speed models the same rack: the same masses, one natural frequency.
  EXPECT_EQ(plan.jobs[0]["scene"]["rack"]["modelled_teeth"],
            plan.jobs[1]["scene"]["rack"]["modelled_teeth"]);
  SweepLimits tight;
  tight.max_particle_steps = 1e3;
  try {
    plan_speed_sweep(req, tight);
    ADD_FAILURE() << "a sweep over the limits was planned";
  } catch (const InvalidJob& e) {
    ASSERT_EQ(e.issues.size(), 2u);
    EXPECT_EQ(e.issues[0].pointer, "/ratios/0");
    EXPECT_EQ(e.issues[1].pointer, "/ratios/1");
  }
}

// A stiffness table given (an earlier measurement's stiffness_cycle.json)
// is the lumped model's: the speeds follow the natural frequency on its
// mean, sqrt(k_mean / m_e) / (2 pi); a table that is no cycle is refused at
// /stiffness with the form it must take.
TEST(SpeedSweep, AGivenStiffnessTableSetsTheSpeeds) {
  const json table = {{"position", {0.1, 0.5, 0.9}}, {"stiffness_N_m", {4e8, 2.7e8, 2.7e8}}};
  const SpeedSweepRequest req =
      read_speed_sweep({{"job", loaded_job()}, {"ratios", {1.0}}, {"stiffness", table}});
  EXPECT_EQ(req.stiffness, "given");
  const SpeedSweepPlan plan = plan_speed_sweep(req, SweepLimits{});
  EXPECT_EQ(plan.stiffness_from, "given");
  EXPECT_EQ(plan.stiffness.value, (std::vector<double>{4e8, 2.7e8, 2.7e8}));
  const double m = plan.lumped_model.at("mass_on_line_of_action_kg").get<double>();
  EXPECT_NEAR(plan.natural_frequency_Hz,
              std::sqrt(plan.stiffness.mean() / m) / (2.0 * std::numbers::pi),
              1e-9 * plan.natural_frequency_Hz);
  EXPECT_EQ(plan_from_document(plan_document(plan)).request.given_stiffness.value,
            plan.stiffness.value);
  json descending = table;
  descending["position"] = {0.5, 0.1, 0.9};
  EXPECT_EQ(pointers_of({{"job", loaded_job()}, {"stiffness", descending}}),
            std::vector<std::string>{"/stiffness"});
  EXPECT_EQ(pointers_of({{"job", loaded_job()}, {"stiffness", {{"position", {0.5}}}}}),
            std::vector<std::string>{"/stiffness"});
}

// A service keeps the plan as a document and reports from it once the
// jobs have run: the plan read back reports exactly as the plan itself, on
// the same summaries (here one speed with a K_v, one that did not run).
TEST(SpeedSweep, APlanReadBackFromItsDocumentReportsAsThePlan) {
  const SpeedSweepRequest req =
      read_speed_sweep({{"job", loaded_job()}, {"ratios", {0.5, 1.0}}, {"steady_periods", 2}});
  const SpeedSweepPlan plan = plan_speed_sweep(req, SweepLimits{});
  const json document = plan_document(plan);
  const SpeedSweepPlan back = plan_from_document(json::parse(document.dump()));
  EXPECT_EQ(plan_document(back), document);
  const std::vector<json> summaries = {
      {{"analysis",
        {{"dynamics",
          {{"K_v", 1.21}, {"dte_pp_m", 3e-6}, {"steady", true}, {"ringing", json::object()}}}}}},
      nullptr};
  const json report = sweep_report(back, summaries, 0.05);
  EXPECT_EQ(report, sweep_report(plan, summaries, 0.05));
  EXPECT_EQ(report.at("K_v_sph").at(0), 1.21);
  EXPECT_TRUE(report.at("K_v_sph").at(1).is_null());
  EXPECT_EQ(report.at("mesh_frequency_Hz").size(), 2u);
}

// A loaded dynamic run ends once its mesh has been steady for the periods
// asked for (scenes::end_on_steady_mesh). On the synthetic start of
// test_steady_mesh.cpp (a ringing decaying with tau = 20 ms on a 100 Hz
// mesh force, steady from 0.05-0.08 s by the detector), ten periods and
// the detector's three of reference put the end 0.13 s later, within the
// one mesh period between its checks.
TEST(SpeedSweep, ARunEndsOnceItsMeshHasBeenSteadyForThePeriodsAskedFor) {
  scenes::GearLayout layout;
  layout.teeth = 12;
  layout.omega = -2.0 * std::numbers::pi * 100.0 / 12.0;  // a 100 Hz mesh
  auto ends = scenes::end_on_steady_mesh(layout, 10);
  History h({"time_s", "contact_force_N"});
  const double F0 = 1000.0, tau = 0.02, rate = 2e4;
  double ended_at = -1.0;
  std::string why;
  for (int k = 0; k <= static_cast<int>(0.5 * rate); ++k) {
    const double t = k / rate, w = 2.0 * std::numbers::pi;
    h.add_row({t, F0 * (1.0 + 0.3 * std::cos(w * 100.0 * t)) +
                      2.0 * F0 * std::exp(-t / tau) * std::cos(w * 730.0 * t)});
    why = ends(h);
    if (!why.empty()) {
      ended_at = t;
      break;
    }
  }
  ASSERT_GT(ended_at, 0.0) << "the run never ended";
  EXPECT_GE(ended_at, 0.05 + 0.13 - 1e-9);
  EXPECT_LE(ended_at, 0.0801 + 0.13 + 0.0101);
  EXPECT_NE(why.find("steady"), std::string::npos) << why;
}

// The lumped model's mass: the rack's, with what is attached, over
// cos^2(alpha) for a pinion held at speed; the attached mass joins the
// guided back's x inertia in proportion to its particles' masses.
TEST(SpeedSweep, AttachedRackMassJoinsTheGuidedBack) {
  json job = loaded_job();
  const PreparedJob bare = prepare_job(job, 1);
  job["scene"]["rack"]["attached_mass_kg"] = 3.0;
  const PreparedJob heavy = prepare_job(job, 1);
  const json& lm0 = bare.scene.description.at("lumped_model");
  const json& lm1 = heavy.scene.description.at("lumped_model");
  const double c = std::cos(20.0 * std::numbers::pi / 180.0);
  const double rack = lm0.at("rack_mass_kg").get<double>();
  EXPECT_NEAR(lm0.at("mass_on_line_of_action_kg").get<double>(), rack / (c * c), 1e-9 * rack);
  EXPECT_NEAR(lm1.at("mass_on_line_of_action_kg").get<double>(), (rack + 3.0) / (c * c),
              1e-9 * rack);
  const double b = 0.02;
  double guided = 0.0;
  const Simulation& sim = heavy.scene.sim;
  for (std::size_t i = sim.bodies[1].begin; i < sim.bodies[1].end; ++i) {
    if (sim.particles.motion[i] == 2) guided += sim.particles.mass[i];
  }
  EXPECT_NEAR(sim.motions[2].inertia_scale, 1.0 + 3.0 / b / guided, 1e-9);
  EXPECT_DOUBLE_EQ(bare.scene.sim.motions[2].inertia_scale, 1.0);
  // The rack's mesh mode (used to relax static checks) slows with it.
  const double w0 = bare.scene.description.at("rack_mesh_mode_rad_s").get<double>();
  const double w1 = heavy.scene.description.at("rack_mesh_mode_rad_s").get<double>();
  EXPECT_NEAR(w1 / w0, std::sqrt(rack / (rack + 3.0)), 1e-9);
  // The sweep's lumped model from the description.
  const gear::dynamics::SdofModel m = sdof_from_description(lm1, 0.03);
  EXPECT_DOUBLE_EQ(m.mass_kg, lm1.at("mass_on_line_of_action_kg").get<double>());
  EXPECT_NEAR(m.stiffness.mean(), lm1.at("mean_stiffness_N_m").get<double>(),
              1e-6 * m.stiffness.mean());
  EXPECT_NEAR(m.load_N, 5000.0 / c, 1e-9);
}

}  // namespace
}  // namespace gearsph::study
