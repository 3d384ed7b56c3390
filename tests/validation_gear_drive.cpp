// The pinion driven by a torque that balances the rack load must carry it
// like a held hub (label "validation": two quasi-static gear runs, ~30 s
// each; the free spin-up is in test_gear_drive.cpp).
#include <gtest/gtest.h>

#include "solver/job/job.hpp"
#include "solver/run/runner.hpp"

namespace gearsph {
namespace {

using nlohmann::json;

TEST(TorqueDrive, BalancedTorqueCarriesTheLoadLikeAHeldHub) {
  // Quasi-static, 1 kN on the rack: a hub held still and a hub driven by
  // the balancing torque T = -F r (rack power F v = T omega, v = omega r)
  // end in the same equilibrium, so tooth 0 carries the same load.
  const double load = 1000.0, pitch_radius = 0.024;
  auto run = [&](bool torque_driven) {
    json pinion = {{"omega_rad_s", 0.0}};
    if (torque_driven) pinion["torque_N_m"] = -load * pitch_radius;
    const json job = {{"name", "torque-balance"},
                      {"scene",
                       {{"type", "rack_pinion"},
                        {"quasi_static", true},
                        {"pinion", pinion},
                        {"rack", {{"velocity_m_s", 0.0}, {"load_N", load}}}}},
                      {"output", {{"frames", 0}}}};
    PreparedJob prepared = prepare_job(job, 1);  // one thread: the same sums every run
    RunResult r = run_job(prepared);
    EXPECT_EQ(r.status, "completed") << r.message;
    return r.summary.at("analysis").at("static_check");
  };
  const json held = run(false), driven = run(true);
  RecordProperty("tooth0_force_held_N", std::to_string(held.at("tooth0_force_N").get<double>()));
  RecordProperty("tooth0_force_driven_N",
                 std::to_string(driven.at("tooth0_force_N").get<double>()));
  const double f_held = held.at("tooth0_force_N").get<double>();
  const double f_driven = driven.at("tooth0_force_N").get<double>();
  EXPECT_NEAR(f_driven, f_held, 0.03 * f_held);
  const double s_held = held.at("nominal_bending_stress_Pa").get<double>();
  const double s_driven = driven.at("nominal_bending_stress_Pa").get<double>();
  EXPECT_NEAR(s_driven, s_held, 0.03 * s_held);
}

}  // namespace
}  // namespace gearsph
