// The fillet stress of the SPH static check at the default particles
// against the built-in finite-element check of the same tooth under the
// same load (docs/gears.md, "Measured: the paper's pinion"). The fillet
// issue's target: the tension peak within 5 % of a converged FE solution.
//
// The FE meshes here are 0.2 mm at the fillets (0.1 mm differs by 0.03 %).
// Two pinions: the paper's at the HPSTC, where the stress fit of the
// particles' stress tensor read 6 % low, and one the defaults were not made
// on (m 5, z 16, 3 kN at the pitch point).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <fstream>
#include <sstream>

#include "fe/external_program.hpp"
#include "fe/fe_check.hpp"
#include "solver/job/job.hpp"
#include "solver/run/execute.hpp"
#include "solver/run/runner.hpp"

namespace gearsph::fe {
namespace {

namespace fs = std::filesystem;

nlohmann::json static_check_job(const nlohmann::json& pinion, double load_N,
                                const std::string& point) {
  nlohmann::json p = pinion;
  p["omega_rad_s"] = 0.0;
  return {{"scene",
           {{"type", "rack_pinion"},
            {"quasi_static", true},
            {"contact_point", point},
            {"pinion", p},
            {"rack", {{"load_N", load_N}, {"velocity_m_s", 0.0}}}}}};
}

void expect_fillet_within_fe(const nlohmann::json& job, const std::string& label) {
  if (const std::string why = fe_unavailable_reason(); !why.empty()) GTEST_SKIP() << why;
  PreparedJob prepared = prepare_job(job, 1);
  const RunResult result = run_job(prepared);
  ASSERT_EQ(result.status, "completed") << result.message;
  const nlohmann::json& sc = result.summary.at("analysis").at("static_check");

  const fs::path dir = fs::temp_directory_path() / ("gearsph-fe-sph-" + label);
  fs::remove_all(dir);
  FeCheckOptions o;
  o.fillet_sizes_m = {0.2e-3};
  o.images = false;
  o.normal_force_N = sc.at("tooth0_force_N").get<double>();
  o.load_radius_m = sc.at("load_radius_m").get<double>();
  const nlohmann::json fe = run_fe_check(prepared.job, dir, o);
  fs::remove_all(dir);

  const nlohmann::json& fit = sc.at("fillet_from_stress_fit");
  struct Row {
    const char* what;
    double sph, fit, fe, tolerance;
  };
  const Row rows[] = {
      {"tension peak", sc.at("fillet_tension_peak_Pa").get<double>(),
       fit.at("tension_peak_Pa").get<double>(), fe.at("fillet_tension_peak_Pa").get<double>(),
       0.05},
      {"compression peak", sc.at("fillet_compression_peak_Pa").get<double>(),
       fit.at("compression_peak_Pa").get<double>(),
       fe.at("fillet_compression_peak_Pa").get<double>(), 0.05},
      // ISO's section is read where the curve is steeper than at the peak.
      {"at 30 degrees", sc.at("fillet_stress_at_iso30_Pa").get<double>(),
       fit.at("at_iso30_Pa").get<double>(), fe.at("fillet_stress_at_iso30_Pa").get<double>(), 0.06},
  };
  for (const Row& r : rows) {
    const double err = r.sph / r.fe - 1.0;
    std::printf(
        "%s %-16s FE %7.2f MPa, SPH stretch %7.2f (%+.1f %%), stress fit %7.2f (%+.1f %%)\n",
        label.c_str(), r.what, 1e-6 * r.fe, 1e-6 * r.sph, 100.0 * err, 1e-6 * r.fit,
        100.0 * (r.fit / r.fe - 1.0));
    EXPECT_LT(std::abs(err), r.tolerance) << label << " " << r.what;
  }
}

TEST(FeSphFillet, PapersPinionAtTheHpstcWithinFivePercentOfFe) {
  expect_fillet_within_fe(static_check_job(nlohmann::json::object(), 1000.0, "hpstc"), "m4z12");
}

TEST(FeSphFillet, AnotherPinionAtThePitchPointWithinFivePercentOfFe) {
  expect_fillet_within_fe(static_check_job({{"module_mm", 5.0}, {"teeth", 16}}, 3000.0, "pitch"),
                          "m5z16");
}

// The rating issue's target: the paper's pinion in nodular iron (GJS 250
// HB, MQ) at 5 kN, rated from the simulation and from the FE check's fillet
// stress and Hertz pressure under the same factors, within 5 %. The job runs
// as `gearsph run` and the service run it (the FE check added to the
// summary), and the FE-based safeties stand in analysis.rating.fe_check.
TEST(FeSphFillet, RatingFromTheFeCheckWithinFivePercentOfTheSimulations) {
  if (const std::string why = fe_unavailable_reason(); !why.empty()) GTEST_SKIP() << why;
  register_fe_check();
  nlohmann::json job = static_check_job(nlohmann::json::object(), 5000.0, "hpstc");
  job["name"] = "rated-fe";
  job["scene"]["material"] = {
      {"E_Pa", 1.73e11},
      {"nu", 0.3},
      {"rho_kg_m3", 7800},
      {"iso6336_5", {{"class", "GJS"}, {"quality", "MQ"}, {"hardness_HB", 250}}},
      {"yield_Pa", 4.2e8}};
  job["scene"]["rating"] = {{"speed_rpm", 143.2}, {"life_h", 1000}};
  job["scene"]["fe_check"] = true;
  job["output"] = {{"frames", 2}};
  const fs::path dir = fs::temp_directory_path() / "gearsph-fe-rating";
  fs::remove_all(dir);
  ExecuteOptions o;
  o.threads = 1;
  const Execution e = execute_job(job, dir, o);
  ASSERT_EQ(e.run.status, "completed") << e.run.message;
  std::ifstream in(dir / "summary.json");
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json summary = nlohmann::json::parse(text.str());
  fs::remove_all(dir);
  ASSERT_TRUE(summary["analysis"].contains("rating")) << summary["analysis"].dump();
  const nlohmann::json& r = summary["analysis"]["rating"];
  ASSERT_TRUE(r.contains("fe_check")) << summary["fe_comparison"].dump();
  const nlohmann::json& fe = r["fe_check"];
  EXPECT_EQ(summary["fe_comparison"]["rating"], fe);
  std::printf("S_F simulated %.4f, FE %.4f (%+.2f %%); S_H simulated %.4f, FE %.4f (%+.2f %%)\n",
              r["simulated"]["S_F"].get<double>(), fe["S_F"].get<double>(),
              100.0 * fe["S_F_difference"].get<double>(), r["simulated"]["S_H_hertz"].get<double>(),
              fe["S_H_hertz"].get<double>(), 100.0 * fe["S_H_difference"].get<double>());
  EXPECT_LT(std::abs(fe["S_F_difference"].get<double>()), 0.05);
  EXPECT_LT(std::abs(fe["S_H_difference"].get<double>()), 0.05);
  EXPECT_NEAR(fe["S_F_simulated"].get<double>(), r["simulated"]["S_F"].get<double>(), 1e-12);
}

}  // namespace
}  // namespace gearsph::fe
