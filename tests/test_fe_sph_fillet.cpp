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

#include "fe/external_program.hpp"
#include "fe/fe_check.hpp"
#include "solver/job/job.hpp"
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

}  // namespace
}  // namespace gearsph::fe
