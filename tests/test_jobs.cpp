// Jobs: the schema's contract (every refusal names the JSON pointer), the
// defaults, the time-step refusal and what the examples promise.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "solver/core/json_schema.hpp"
#include "solver/integrate/integrator.hpp"
#include "solver/integrate/stability.hpp"
#include "solver/job/job.hpp"
#include "solver/run/runner.hpp"
#include "tests/support/job_issues.hpp"

namespace gearsph {
namespace {

using nlohmann::json;

using testing_support::issues_of;

bool has_issue(const std::vector<JobIssue>& issues, const std::string& pointer,
               const std::string& phrase) {
  for (const JobIssue& i : issues) {
    if (i.pointer == pointer && i.message.find(phrase) != std::string::npos) return true;
  }
  return false;
}

std::string describe(const std::vector<JobIssue>& issues) {
  std::ostringstream s;
  for (const JobIssue& i : issues) s << i.pointer << ": " << i.message << "\n";
  return s.str();
}

const json kPlate = {{"scene", {{"type", "plate"}}}, {"time", {{"end_s", 0.001}}}};

TEST(Jobs, ThreadsFollowTheSceneSizeUnlessSet) {
  // One thread per kParticlesPerThread, at least one, at most the cap.
  EXPECT_EQ(threads_for(918, 2), 2);
  EXPECT_EQ(threads_for(kParticlesPerThread - 1, 2), 1);
  EXPECT_EQ(threads_for(2 * kParticlesPerThread, 2), 2);
  EXPECT_EQ(threads_for(2 * kParticlesPerThread, 1), 1);
  EXPECT_EQ(threads_for(100 * kParticlesPerThread, 8), 8);
  EXPECT_EQ(threads_for(0, 0), 1);
  // The seed paper's case (918 particles, 1e6 steps): a trial of 1 and 2 threads
  // unless the command line or the job says.
  const json gear = {{"scene", {{"type", "rack_pinion"}}}};
  const PreparedJob paper = prepare_job(gear, 0, 2);
  EXPECT_EQ(paper.threads_by, "trial");
  EXPECT_EQ(paper.trial_threads, 2);
  EXPECT_EQ(paper.scene.sim.threads, 1);                  // until the trial has run
  EXPECT_EQ(prepare_job(gear, 0, 1).threads_by, "size");  // nothing to try
  EXPECT_EQ(prepare_job(gear, 2).scene.sim.threads, 2);   // the command line's --threads
  EXPECT_EQ(prepare_job(gear, 2).threads_by, "caller");
  json own = gear;
  own["threads"] = 2;
  EXPECT_EQ(prepare_job(own, 0, 4).scene.sim.threads, 2);
  EXPECT_EQ(prepare_job(own, 0, 4).threads_by, "job");
  EXPECT_EQ(prepare_job(own, 0, 1).scene.sim.threads, 1);  // a server's share caps it
  // A short run is not worth a trial: one thread.
  json short_run = gear;
  short_run["time"] = {{"end_s", 1e-5}};
  const PreparedJob brief = prepare_job(short_run, 0, 2);
  ASSERT_LT(double(brief.scene.sim.particles.n) * double(brief.steps), kTrialParticleSteps);
  EXPECT_EQ(brief.threads_by, "size");
  EXPECT_EQ(brief.scene.sim.threads, 1);
}

TEST(Jobs, ARunRecordsAtMostTheSamplesAndFramesAskedFor) {
  // 1.9 steps a point: sampling every step would give 1.9x the rows.
  const std::int64_t steps = prepare_job(kPlate, 1).steps;
  ASSERT_GE(steps, 40);
  json job = kPlate;
  const std::int64_t wanted = steps * 10 / 19;
  job["output"] = {{"history_points", wanted}, {"frames", wanted}};
  PreparedJob prepared = prepare_job(job, 1);
  EXPECT_LE(prepared.frames, wanted + 1);  // with the initial state
  EXPECT_GE(prepared.frames, wanted / 2);
  const RunResult r = run_job(prepared);
  ASSERT_EQ(r.status, "completed") << r.message;
  EXPECT_LE(r.history.rows(), static_cast<std::size_t>(wanted + 1));
  EXPECT_GE(r.history.rows(), static_cast<std::size_t>(wanted / 2));
  EXPECT_EQ(r.history.column("time_s").back(), prepared.scene.sim.time);  // the last step
}

// A scene may end its run before the last step once the run holds what it
// was run for (Scene::ends_early: a dynamic run's steady mesh). The run
// then completes there with the reason in its summary, and its history
// ends at the step it stopped on.
TEST(Jobs, ARunEndsEarlyWhenItsSceneSaysSo) {
  PreparedJob prepared = prepare_job(kPlate, 1);
  const std::int64_t steps = prepared.steps;
  ASSERT_GE(steps, 40);
  prepared.scene.ends_early = [](const History& h) {
    return h.rows() >= 5 ? std::string("five rows") : std::string();
  };
  const RunResult r = run_job(prepared);
  ASSERT_EQ(r.status, "completed") << r.message;
  EXPECT_EQ(r.history.rows(), 5u);
  EXPECT_LT(r.steps_done, steps);
  EXPECT_EQ(r.summary.at("ended_early"), "five rows");
  EXPECT_EQ(r.history.column("time_s").back(), prepared.scene.sim.time);
}

// /scene/steady_mesh_periods ends a loaded dynamic run: a static check and
// a run without a load are refused at it, with the reason.
TEST(Jobs, TheSteadyMeshEndIsAskedOnlyOfALoadedDynamicRun) {
  const json coarse = {{"particles", "lattice"}, {"spacing_mm", 2.0}};
  const json still = {{"scene",
                       {{"type", "rack_pinion"},
                        {"quasi_static", true},
                        {"steady_mesh_periods", 20},
                        {"pinion", {{"omega_rad_s", 0.0}}},
                        {"rack", {{"velocity_m_s", 0.0}, {"load_N", 1000.0}}}}},
                      {"discretization", coarse}};
  auto issues = issues_of(still);
  EXPECT_TRUE(has_issue(issues, "/scene/steady_mesh_periods", "quasi-static")) << describe(issues);
  const json unloaded = {{"scene", {{"type", "rack_pinion"}, {"steady_mesh_periods", 20}}},
                         {"discretization", coarse}};
  issues = issues_of(unloaded);
  EXPECT_TRUE(has_issue(issues, "/scene/steady_mesh_periods", "not loaded")) << describe(issues);
  json loaded = unloaded;
  loaded["scene"]["rack"] = {{"load_N", 1000.0}};
  EXPECT_TRUE(issues_of(loaded).empty()) << describe(issues_of(loaded));
}

TEST(Jobs, ADefaultHistoryIsSampledByTimeUnlessTheSceneReadsEveryStep) {
  // A short run that names no history_points: a row every 10 steps, not
  // one per step (kDefaultHistoryMinSteps).
  const PreparedJob plate = prepare_job(kPlate, 1);
  ASSERT_LT(plate.steps, kDefaultHistoryPoints * kDefaultHistoryMinSteps);
  EXPECT_EQ(plate.history_every, kDefaultHistoryMinSteps);
  // Named, the points are taken as asked.
  json asked = kPlate;
  asked["output"] = {{"history_points", plate.steps}};
  EXPECT_EQ(prepare_job(asked, 1).history_every, 1);
  // A long run spreads its default rows over the run.
  json long_run = kPlate;
  long_run["time"] = {{"end_s", 0.001 * 20 * double(kDefaultHistoryPoints) / double(plate.steps)}};
  EXPECT_GT(prepare_job(long_run, 1).history_every, kDefaultHistoryMinSteps);
  // An impact's contact time is read off the history: every step.
  const json impact = {{"scene", {{"type", "bar_impact"}}}};
  const PreparedJob bars = prepare_job(impact, 1);
  ASSERT_LT(bars.steps, kDefaultHistoryPoints);
  EXPECT_EQ(bars.history_every, 1);
}

TEST(Jobs, ALargeSceneTakesThreadsBySizeWithoutATrial) {
  const json plate = {{"scene", {{"type", "plate"}}},
                      {"discretization", {{"spacing_m", 0.0003}}},
                      {"time", {{"end_s", 1e-6}}}};
  const PreparedJob job = prepare_job(plate, 0, 2);
  ASSERT_GE(job.scene.sim.particles.n, kThreadsWithoutTrial);
  EXPECT_EQ(job.threads_by, "size");
  EXPECT_EQ(job.scene.sim.threads, 2);
}

TEST(Jobs, SchemaIsValidDraft07ForOurValidator) {
  EXPECT_NO_THROW(jsonschema::Validator{job_schema()});
  EXPECT_EQ(job_schema().at("$schema"), "http://json-schema.org/draft-07/schema#");
}

TEST(Jobs, ExamplesAreValidAndBuild) {
  const std::filesystem::path dir = std::filesystem::path(GEARSPH_SOURCE_DIR) / "schemas/examples";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    // Rating documents have their own schema (test_rating.cpp).
    if (entry.path().filename().string().rfind("rating-", 0) == 0) continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    const json job = parse_job_text(text.str());
    EXPECT_NO_THROW(validate_job(job)) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 3);
}

TEST(Jobs, DefaultsAreFilledFromTheSchema) {
  const json full = validate_job(kPlate);
  EXPECT_EQ(full.at("name"), "job");
  EXPECT_EQ(full.at("method").at("formulation"), "total_lagrangian");
  EXPECT_EQ(full.at("method").at("gradient_correction"), "quadratic");
  EXPECT_EQ(full.at("method").at("artificial_viscosity").at("alpha"), 1.0);
  EXPECT_EQ(full.at("discretization").at("kernel"), "seed_quartic");
  EXPECT_EQ(full.at("scene").at("length_m"), 0.2);
  EXPECT_EQ(full.at("scene").at("material").at("E_Pa"), 2e6);
  EXPECT_FALSE(full.at("time").contains("cfl"));  // neither dt nor cfl: auto step
}

TEST(Jobs, MalformedJsonIsRefusedWithAPosition) {
  try {
    parse_job_text("{\"scene\": {\"type\": \"plate\",}}");
    FAIL() << "malformed JSON accepted";
  } catch (const InvalidJob& e) {
    ASSERT_EQ(e.issues.size(), 1u);
    EXPECT_EQ(e.issues[0].pointer, "");
    EXPECT_NE(e.issues[0].message.find("not valid JSON"), std::string::npos);
    EXPECT_NE(e.issues[0].message.find("line 1"), std::string::npos);
  }
}

TEST(Jobs, EveryViolationNamesItsPointer) {
  json job = kPlate;
  job["scene"]["type"] = "plat";
  auto issues = issues_of(job);
  EXPECT_TRUE(has_issue(issues, "/scene/type", "did you mean \"plate\"")) << describe(issues);

  job = kPlate;
  job["scene"]["thickness_m"] = -0.02;
  issues = issues_of(job);
  EXPECT_TRUE(has_issue(issues, "/scene/thickness_m", "greater than 0")) << describe(issues);

  job = kPlate;
  job["scene"]["lenght_m"] = 0.3;
  issues = issues_of(job);
  EXPECT_TRUE(has_issue(issues, "/scene/lenght_m", "length_m")) << describe(issues);

  job = kPlate;
  job["discretization"] = {{"kernel", "gaussian"}};
  issues = issues_of(job);
  EXPECT_TRUE(has_issue(issues, "/discretization/kernel", "seed_quartic")) << describe(issues);

  job = kPlate;
  job["scene"]["material"] = {{"E_Pa", 2e11}, {"nu", 0.7}};
  issues = issues_of(job);
  EXPECT_TRUE(has_issue(issues, "/scene/material/nu", "at most 0.49")) << describe(issues);
  EXPECT_TRUE(has_issue(issues, "/scene/material/rho_kg_m3", "is required")) << describe(issues);

  job = kPlate;
  job["time"] = {{"dt_s", 1e-6}, {"cfl", 0.3}};
  issues = issues_of(job);
  EXPECT_TRUE(has_issue(issues, "/time/cfl", "not both")) << describe(issues);

  job = kPlate;
  job["discretization"] = {{"spacing_m", 0.002}, {"spacing_mm", 2}};
  issues = issues_of(job);
  EXPECT_TRUE(has_issue(issues, "/discretization/spacing_mm", "not both")) << describe(issues);

  issues = issues_of(json::array());
  EXPECT_TRUE(has_issue(issues, "", "object")) << describe(issues);
}

TEST(Jobs, SceneLimitsAreExplained) {
  json job = kPlate;
  job["discretization"] = {{"spacing_m", 0.01}};  // 2 particles across 0.02 m
  auto issues = issues_of(job);
  EXPECT_TRUE(has_issue(issues, "/discretization", "across the plate thickness"))
      << describe(issues);

  job = kPlate;
  job["scene"]["clamp_length_m"] = 0.002;
  issues = issues_of(job);
  EXPECT_TRUE(has_issue(issues, "/scene/clamp_length_m", "kernel support")) << describe(issues);
}

TEST(Jobs, AResolvedContactIsAskedOnlyWhereItApplies) {
  const json held = {{"type", "rack_pinion"},
                     {"quasi_static", true},
                     {"resolve_contact", true},
                     {"pinion", {{"omega_rad_s", 0.0}}},
                     {"rack", {{"velocity_m_s", 0.0}, {"load_N", 1000.0}}}};
  json dynamic = {{"scene", held}};
  dynamic["scene"]["quasi_static"] = false;
  auto issues = issues_of(dynamic);
  EXPECT_TRUE(has_issue(issues, "/scene/resolve_contact", "quasi_static")) << describe(issues);

  const json lattice = {
      {"scene", held},
      {"discretization", {{"particles", "lattice"}, {"contact_spacing_mm", 0.02}}}};
  issues = issues_of(lattice);
  EXPECT_TRUE(has_issue(issues, "/discretization/contact_spacing_mm", "body_fitted"))
      << describe(issues);

  const json coarse = {{"scene", held}, {"discretization", {{"contact_spacing_mm", 0.5}}}};
  issues = issues_of(coarse);
  EXPECT_TRUE(has_issue(issues, "/discretization/contact_spacing_m", "fine spacing"))
      << describe(issues);
}

// A pinion of contact ratio below 1 (z 11, m 9, 21 degrees, x -0.3:
// 0.95) is outside what ISO 6336 method B rates. A static check of it that
// asks for no rating runs, and says why it is not rated when its materials
// carry strength; one that asks for a rating is refused at /scene/rating.
// Before, every such static check was refused (ISO 6336-1's K_v beside the
// lumped model refused the pair), and the accuracy map lost the case.
TEST(Jobs, AStaticCheckOutsideTheRatingRunsUnrated) {
  json job = {{"scene",
               {{"type", "rack_pinion"},
                {"quasi_static", true},
                {"contact_point", "hpstc"},
                {"pinion",
                 {{"module_mm", 9.0},
                  {"teeth", 11},
                  {"pressure_angle_deg", 21.0},
                  {"profile_shift", -0.3},
                  {"backlash_mm", 0.0},
                  {"omega_rad_s", 0.0}}},
                {"rack", {{"velocity_m_s", 0.0}, {"load_N", 6600.0}}}}},
              {"output", {{"frames", 0}}}};
  EXPECT_NO_THROW(prepare_job(job, 1));
  job["scene"]["material"] = {
      {"E_Pa", 1.73e11},
      {"nu", 0.3},
      {"rho_kg_m3", 7800},
      {"iso6336_5", {{"class", "GJS"}, {"quality", "MQ"}, {"hardness_HB", 250}}}};
  job["scene"]["pinion"]["omega_rad_s"] = 1.0;  // a speed for K_v
  EXPECT_NO_THROW(prepare_job(job, 1));
  job["scene"]["rating"] = json::object();
  auto issues = issues_of(job);
  EXPECT_TRUE(has_issue(issues, "/scene/rating", "contact ratio")) << describe(issues);
}

// ISO 53's cutter tip radius (0.38 modules) does not fit a 25-degree tooth
// space at the standard depths: a job that gives none gets nine tenths of
// the largest that fits both the pinion's and the rack's space, and says so;
// one that gives too large a radius is told the largest.
TEST(Jobs, CutterTipRadiusFollowsThePressureAngle) {
  json job = {{"scene",
               {{"type", "rack_pinion"},
                {"quasi_static", true},
                {"pinion", {{"omega_rad_s", 0.0}, {"teeth", 18}, {"pressure_angle_deg", 25}}},
                {"rack", {{"load_N", 1000.0}, {"velocity_m_s", 0.0}}}}}};
  const PreparedJob prepared = prepare_job(job, 1);
  const double coef =
      prepared.scene.description.at("pinion").at("cutter_tip_radius_coef").get<double>();
  EXPECT_GT(coef, 0.25);
  EXPECT_LT(coef, 0.33);
  // At 20 degrees, ISO 53's own.
  job["scene"]["pinion"]["pressure_angle_deg"] = 20;
  EXPECT_EQ(
      prepare_job(job, 1).scene.description.at("pinion").at("cutter_tip_radius_coef").get<double>(),
      0.38);
  job["scene"]["pinion"]["pressure_angle_deg"] = 25;
  job["scene"]["pinion"]["cutter_tip_radius_coef"] = 0.4;
  const auto issues = issues_of(job);
  EXPECT_TRUE(has_issue(issues, "/scene/pinion/cutter_tip_radius_coef", "the largest is 0.3"))
      << describe(issues);
  // One that fits the pinion's space (widened by its backlash) but not the
  // rack's is refused at the same field, not as a rack that cannot be built.
  job["scene"]["pinion"]["cutter_tip_radius_coef"] = 0.33;
  const auto narrow = issues_of(job);
  EXPECT_TRUE(has_issue(narrow, "/scene/pinion/cutter_tip_radius_coef", "the largest is 0.31"))
      << describe(narrow);
}

// The paper's lattice runs as published, at its 4e-8 s; body-fitted
// particles, the default, take 80 % of the stable limit their finest
// particle sets, which at the fillets' rho_F / 5 is longer than the paper's.
TEST(Jobs, PapersLatticeKeepsItsStepAndBodyFittedParticlesTakeTheAutomaticOne) {
  json job = {{"scene", {{"type", "rack_pinion"}}}};
  const PreparedJob fitted = prepare_job(job, 1);
  EXPECT_EQ(fitted.time_step.chosen_by, "auto");
  EXPECT_NEAR(fitted.time_step.dt, 0.8 * fitted.time_step.dt_limit, 1e-20);
  EXPECT_GT(fitted.time_step.dt, 4e-8);
  job["discretization"] = {{"particles", "lattice"}};
  const PreparedJob lattice = prepare_job(job, 1);
  EXPECT_EQ(lattice.time_step.chosen_by, "scene default");
  EXPECT_EQ(lattice.time_step.dt, 4e-8);
  EXPECT_EQ(lattice.steps, 1000000);
}

TEST(Jobs, FixedTimeStepAboveTheLimitIsRefusedWithTheLimit) {
  json job = kPlate;
  job["time"]["dt_s"] = 1e-3;
  const auto issues = issues_of(job);
  ASSERT_EQ(issues.size(), 1u) << describe(issues);
  EXPECT_EQ(issues[0].pointer, "/time/dt_s");
  EXPECT_NE(issues[0].message.find("above the stable limit"), std::string::npos);
  EXPECT_NE(issues[0].message.find("dt <= 1.5"), std::string::npos) << issues[0].message;

  job["time"]["dt_s"] = 1e-5;  // below the limit of ~1.5e-5 s
  EXPECT_NO_THROW(prepare_job(job, 1));

  job["time"].erase("dt_s");
  job["time"]["cfl"] = 2.0;
  const auto cfl_issues = issues_of(job);
  ASSERT_EQ(cfl_issues.size(), 1u);
  EXPECT_EQ(cfl_issues[0].pointer, "/time/cfl");
  EXPECT_NE(cfl_issues[0].message.find("Courant number"), std::string::npos);
}

// The stable-step estimate sums in a fixed order on any number of threads
// (integrate/stability.cpp), so a job's step does not depend on them.
TEST(Jobs, TheStableStepDoesNotDependOnTheThreads) {
  json job = kPlate;
  job["discretization"]["spacing_m"] = 0.001;  // 4,000 particles: windows in every chunk
  PreparedJob prepared = prepare_job(job, 1);
  Simulation& sim = prepared.scene.sim;
  ASSERT_GT(sim.method.viscosity.alpha, 0.0);  // the damping operator is estimated
  const StabilityLimit one = estimate_stability_limit(sim);
  ASSERT_GT(one.damping_rate, 0.0);
  EXPECT_EQ(one.dt_limit, prepared.time_step.dt_limit);
  for (int threads : {2, 3}) {
    sim.threads = threads;
    const StabilityLimit many = estimate_stability_limit(sim);
    EXPECT_EQ(many.omega_max, one.omega_max) << threads << " threads";
    EXPECT_EQ(many.damping_rate, one.damping_rate) << threads << " threads";
    EXPECT_EQ(many.dt_limit, one.dt_limit) << threads << " threads";
  }
}

// The estimate runs on the scene itself (integrate/stability.cpp): an
// updated-Lagrangian scene gets back its state to the bit, initial stress
// included, and no reference pairs; a total-Lagrangian scene keeps the pairs
// for its run, which then goes exactly as with pairs built afresh.
TEST(Jobs, TheStableStepEstimatePutsTheSceneBack) {
  json disk = {{"name", "disk"},
               {"scene",
                {{"type", "spinning_disk"},
                 {"initial_stress_Pa", {{"xx", 2e6}, {"yy", -1e6}, {"xy", 5e5}}}}},
               {"method", {{"formulation", "updated_lagrangian"}}},
               {"output", {{"frames", 0}}}};
  PreparedJob ul = prepare_job(disk, 2);
  Simulation& sim = ul.scene.sim;
  EXPECT_FALSE(sim.reference.built());
  const Particles before = sim.particles;
  ASSERT_TRUE(std::any_of(before.sxx.begin(), before.sxx.end(), [](double s) { return s != 0; }));
  const MethodConfig method = sim.method;
  const StabilityLimit limit = estimate_stability_limit(sim);
  EXPECT_EQ(limit.dt_limit, ul.time_step.dt_limit);
  EXPECT_FALSE(sim.reference.built());
  EXPECT_EQ(sim.method.formulation, method.formulation);
  EXPECT_EQ(sim.method.viscosity.alpha, method.viscosity.alpha);
  EXPECT_EQ(sim.method.hourglass.coefficient, method.hourglass.coefficient);
  const Particles& after = sim.particles;
  for (auto field : {&Particles::x, &Particles::y, &Particles::vx, &Particles::vy, &Particles::p,
                     &Particles::sxx, &Particles::syy, &Particles::szz, &Particles::sxy,
                     &Particles::rho, &Particles::fxx, &Particles::fyy, &Particles::ax}) {
    EXPECT_TRUE(after.*field == before.*field);
  }

  json plate = kPlate;
  plate["discretization"]["spacing_m"] = 0.001;
  PreparedJob tl = prepare_job(plate, 2);
  Simulation& kept = tl.scene.sim;
  ASSERT_TRUE(kept.reference.built());
  Simulation fresh = kept;
  fresh.reference = ReferencePairs();
  integrate::initialise(kept);
  integrate::initialise(fresh);
  for (int s = 0; s < 50; ++s) {
    integrate::step(kept);
    integrate::step(fresh);
  }
  EXPECT_TRUE(kept.particles.x == fresh.particles.x);
  EXPECT_TRUE(kept.particles.vy == fresh.particles.vy);
  EXPECT_TRUE(kept.particles.sxx == fresh.particles.sxx);
}

TEST(Jobs, AutomaticStepIsAFractionOfTheLimit) {
  const PreparedJob job = prepare_job(kPlate, 1);
  EXPECT_EQ(job.time_step.chosen_by, "auto");
  EXPECT_NEAR(job.time_step.dt, kAutoStepFraction * job.time_step.dt_limit, 1e-18);
  EXPECT_GT(job.steps, 0);
}

}  // namespace
}  // namespace gearsph
