// The run's health check (solver/diagnostics/health.hpp): each detector
// fires on a case built to fail and stays quiet on the same case run with a
// method that holds; its message reaches summary.json, the CLI and the job
// service's status. Small scenes: each test runs in about a second.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "solver/diagnostics/health.hpp"
#include "solver/integrate/integrator.hpp"
#include "solver/job/job.hpp"
#include "solver/physics/simulation.hpp"
#include "solver/run/runner.hpp"

namespace gearsph {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// A 50 mm x 10 mm rubber-like strip, dx 1 mm (500 particles), pulled by its
// grips to `strain` over five transit periods (about 700 steps).
json strip(const json& method, double strain = 0.01, const std::string& kernel = "seed_quartic") {
  return {{"scene",
           {{"type", "tension_strip"},
            {"length_m", 0.05},
            {"thickness_m", 0.01},
            {"peak_strain", strain}}},
          {"discretization", {{"spacing_m", 0.001}, {"kernel", kernel}}},
          {"method", method},
          {"output", {{"history_points", 400}, {"frames", 0}}}};
}
const json kUlPaper = {{"formulation", "updated_lagrangian"},
                       {"gradient_correction", "none"},
                       {"artificial_stress", {{"epsilon", 0.0}}}};
const json kTl = {{"formulation", "total_lagrangian"}};

RunResult run(const json& job) {
  PreparedJob p = prepare_job(job, 1);
  return run_job(p);
}

const json& stop_event(const RunResult& r) {
  static const json none = json::object();
  for (const json& e : r.summary.at("health").at("events")) {
    if (e.at("level") == "stop") return e;
  }
  return none;
}

void expect_quiet(const RunResult& r) {
  EXPECT_EQ(r.status, "completed") << r.message;
  EXPECT_EQ(r.summary.at("health").at("status"), "ok") << r.summary.at("health").dump(2);
  EXPECT_TRUE(r.summary.at("warnings").empty());
}

// ---- particle disorder -------------------------------------------------------

TEST(StabilityDetectors, DisorderStopsTheTensileInstability) {
  // Plain UL SPH with the cubic spline clumps at about 5 % strain.
  const RunResult r = run(strip(kUlPaper, 0.1, "cubic_spline"));
  ASSERT_EQ(r.status, "diverged") << r.message;
  const json& e = stop_event(r);
  ASSERT_FALSE(e.empty()) << r.summary.at("health").dump(2);
  EXPECT_EQ(e.at("detector"), "particle_disorder");
  EXPECT_LT(e.at("value").get<double>(), 0.5);
  // The message says what, when, where and what to change.
  EXPECT_NE(r.message.find("diverged at step"), std::string::npos);
  EXPECT_NE(r.message.find("health check stopped the run (particle_disorder = "), std::string::npos)
      << r.message;
  EXPECT_NE(r.message.find("tensile instability"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("total-Lagrangian"), std::string::npos) << r.message;
  EXPECT_EQ(r.summary.at("status"), "diverged");
  EXPECT_EQ(r.summary.at("message"), r.message);
  EXPECT_EQ(r.summary.at("health").at("status"), "stopped");
}

TEST(StabilityDetectors, DisorderQuietWithArtificialStress) {
  // The same strip, same kernel, with Monaghan's remedy.
  json method = kUlPaper;
  method["artificial_stress"] = {{"epsilon", 0.3}, {"n", 4}};
  const RunResult r = run(strip(method, 0.1, "cubic_spline"));
  EXPECT_EQ(r.status, "completed") << r.message;
  EXPECT_GT(r.summary.at("health").at("measures").at("min_spacing_over_dx").get<double>(), 0.8);
  for (const json& e : r.summary.at("health").at("events")) {
    EXPECT_NE(e.at("detector"), "particle_disorder") << e.dump();
  }
}

// ---- energy growth -------------------------------------------------------------

json strip_at(double dt_over_limit) {
  json job = strip(kTl);
  const PreparedJob probe = prepare_job(job, 1);
  job["time"] = {{"dt_s", dt_over_limit * probe.time_step.dt_limit}, {"allow_unstable", true}};
  return job;
}

TEST(StabilityDetectors, EnergyGrowthStopsAnUnstableStep) {
  const RunResult r = run(strip_at(1.5));
  ASSERT_EQ(r.status, "diverged") << r.message;
  const json& e = stop_event(r);
  ASSERT_FALSE(e.empty()) << r.message;
  EXPECT_EQ(e.at("detector"), "energy_growth");
  EXPECT_GT(e.at("value").get<double>(), 0.1);
  EXPECT_NE(r.message.find("energy balance grew"), std::string::npos) << r.message;
  // Stopped before anything became NaN: the guard would have said so.
  EXPECT_EQ(r.message.find("non-finite"), std::string::npos);
}

TEST(StabilityDetectors, EnergyGrowthQuietAtTheAutomaticStep) {
  const RunResult r = run(strip(kTl));
  expect_quiet(r);
  // The balance moves by a few percent (the grips' work), far below the limit.
  EXPECT_LT(std::abs(r.summary.at("health").at("measures").at("energy_growth").get<double>()),
            0.05);
}

// ---- penetration ---------------------------------------------------------------

// Two 20 mm x 5 mm steel bars at +-20 m/s, dx 0.5 mm, over one contact time.
json bars(double D) {
  return {{"scene",
           {{"type", "bar_impact"},
            {"length_m", 0.02},
            {"thickness_m", 0.005},
            {"velocity_m_s", 20.0}}},
          {"discretization", {{"spacing_m", 0.0005}}},
          {"method", {{"contact", {{"model", "seed_penalty"}, {"D", D}}}}},
          {"time", {{"end_s", 8e-6}}},
          {"output", {{"history_points", 200}, {"frames", 0}}}};
}

TEST(StabilityDetectors, PenetrationStopsASoftContact) {
  // A contact a thousand times softer than calibrated: the bars run into each other.
  const RunResult r = run(bars(0.001));
  ASSERT_EQ(r.status, "diverged") << r.message;
  const json& e = stop_event(r);
  ASSERT_FALSE(e.empty()) << r.message;
  EXPECT_EQ(e.at("detector"), "penetration");
  EXPECT_NE(r.message.find("bodies overlap"), std::string::npos) << r.message;
}

TEST(StabilityDetectors, PenetrationQuietWithTheCalibratedContact) {
  const RunResult r = run(bars(1.0));
  expect_quiet(r);
  EXPECT_LT(r.summary.at("health").at("measures").at("max_penetration_over_dx").get<double>(),
            0.25);
}

// ---- NaN (the divergence guard) with warnings only ------------------------------

TEST(StabilityDetectors, WarnModeRecordsAndTheGuardStillStopsNaN) {
  json job = strip_at(3.0);
  job["health"] = {{"on_failure", "warn"}};
  const RunResult r = run(job);
  ASSERT_EQ(r.status, "diverged") << r.message;
  // No health stop: the guard named the quantity that went bad.
  EXPECT_NE(r.message.find("diverged at step"), std::string::npos) << r.message;
  EXPECT_TRUE(stop_event(r).empty());
  // ... after the monitor had warned about the energy.
  bool energy_warning = false;
  for (const json& e : r.summary.at("health").at("events")) {
    energy_warning |= e.at("detector") == "energy_growth" && e.at("level") == "warning";
  }
  EXPECT_TRUE(energy_warning) << r.summary.at("health").dump(2);
  EXPECT_FALSE(r.summary.at("warnings").empty());
}

// ---- zig-zag indicator -----------------------------------------------------------

TEST(StabilityDetectors, ZigzagIndicatorSeesACheckerboardNotASmoothField) {
  for (const json& method : {kTl, kUlPaper}) {
    PreparedJob job = prepare_job(strip(method), 1);
    Simulation& sim = job.scene.sim;
    integrate::initialise(sim);
    Particles& p = sim.particles;
    const double dx = sim.discretization.dx;
    // Smooth: a linear shear stress along the strip.
    for (std::size_t i = 0; i < p.n; ++i) p.sxy[i] = 1e6 * (p.x[i] / 0.05 - 0.5);
    EXPECT_LT(diagnostics::zigzag_indicator(sim), 0.1);
    // Checkerboard: the shear stress alternates between neighbours.
    for (std::size_t i = 0; i < p.n; ++i) {
      const long a = std::lround(p.x[i] / dx - 0.5), b = std::lround(p.y[i] / dx - 0.5);
      p.sxy[i] = 1e6 * ((a + b) % 2 == 0 ? 1.0 : -1.0);
    }
    EXPECT_GT(diagnostics::zigzag_indicator(sim), 0.9);  // 1 with the 8 lattice neighbours
  }
}

TEST(StabilityDetectors, ZigzagWarningReachesTheSummary) {
  // A warning threshold below any real field: every run warns, none stops.
  json job = strip(kTl);
  job["health"] = {{"zigzag_warning", 1e-6}};
  const RunResult r = run(job);
  EXPECT_EQ(r.status, "completed") << r.message;
  EXPECT_EQ(r.summary.at("health").at("status"), "warning");
  ASSERT_EQ(r.summary.at("warnings").size(), 1u);  // once per detector, not per sample
  EXPECT_NE(r.summary.at("message").get<std::string>().find("zig-zag"), std::string::npos);
}

// ---- job contract ------------------------------------------------------------------

TEST(StabilityDetectors, HealthOptionsAreValidatedAndDefaulted) {
  const json filled = validate_job(strip(kTl));
  EXPECT_EQ(filled.at("health").at("on_failure"), "stop");
  EXPECT_DOUBLE_EQ(filled.at("health").at("energy_growth_max").get<double>(), 0.3);
  json bad = strip(kTl);
  bad["health"] = {{"on_failure", "ignore"}};
  EXPECT_THROW(validate_job(bad), InvalidJob);
  bad["health"] = {{"min_spacing_over_dx", 1.5}};
  EXPECT_THROW(validate_job(bad), InvalidJob);
}

// ---- the CLI: exit status 3 and the message on stderr ------------------------------

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(StabilityDetectors, CliReportsTheDetectorAndExitsDiverged) {
  const fs::path dir = fs::temp_directory_path() / "gearsph_stability_cli";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "job.json") << strip(kUlPaper, 0.1, "cubic_spline").dump();
  const std::string cmd = std::string(GEARSPH_BINARY) + " run " + (dir / "job.json").string() +
                          " --out " + (dir / "out").string() + " --threads 1 --quiet 2> " +
                          (dir / "stderr.txt").string();
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 3);
  EXPECT_NE(slurp(dir / "stderr.txt").find("particles of body 'strip' came within"),
            std::string::npos);
  const json summary = json::parse(slurp(dir / "out/summary.json"));
  EXPECT_EQ(summary.at("health").at("status"), "stopped");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gearsph
