// The lumped model's mesh stiffness over one mesh cycle from quasi-static
// checks of the same pair (solver/study/mesh_stiffness_cycle.hpp): the
// table's assembly from given readings and the plan's refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "solver/job/job.hpp"
#include "solver/study/mesh_stiffness_cycle.hpp"

namespace gearsph::study {
namespace {

using json = nlohmann::json;

TEST(MeshStiffnessCycle, TableFromReadings) {
  // Two double-contact readings, then single-contact ones, for eps = 1.3.
  const std::vector<double> s = {0.05, 0.2, 0.4, 0.6, 0.8};
  const std::vector<double> k = {5e8, 5.2e8, 3e8, 3.1e8, 2.9e8};
  const gear::dynamics::MeshCycleTable t = mesh_cycle_table(s, k);
  EXPECT_DOUBLE_EQ(t.at(0.2), 5.2e8);
  EXPECT_DOUBLE_EQ(t.at(0.5), 0.5 * (3e8 + 3.1e8));
  // Across the period's end, linear from s = 0.8 to 1.05.
  EXPECT_NEAR(t.at(0.925), 0.5 * (2.9e8 + 5e8), 1.0);
  const MeshCycleLevels lv = mesh_cycle_levels(t, 1.3);
  EXPECT_DOUBLE_EQ(lv.double_pair_N_m, 0.5 * (5e8 + 5.2e8));
  EXPECT_DOUBLE_EQ(lv.single_pair_N_m, (3e8 + 3.1e8 + 2.9e8) / 3.0);
  // The trapezoids of the piecewise-linear cycle.
  const double area = 0.15 * (5e8 + 5.2e8) / 2 + 0.2 * (5.2e8 + 3e8) / 2 + 0.2 * (3e8 + 3.1e8) / 2 +
                      0.2 * (3.1e8 + 2.9e8) / 2 + 0.25 * (2.9e8 + 5e8) / 2;
  EXPECT_NEAR(lv.mean_N_m, area, 1e-6 * area);
  // Bad readings are refused.
  EXPECT_THROW(mesh_cycle_table({0.5, 0.2}, {1e8, 1e8}), std::invalid_argument);
  EXPECT_THROW(mesh_cycle_table({0.2, 1.0}, {1e8, 1e8}), std::invalid_argument);
  EXPECT_THROW(mesh_cycle_table({0.2, 0.5}, {1e8, -1.0}), std::invalid_argument);
  EXPECT_THROW(mesh_cycle_table({0.2}, {1e8}), std::invalid_argument);
}

// The paper's pair at 5 kN, dynamic, on a 1 mm lattice.
json dynamic_job() {
  return validate_job({{"name", "cycle-test"},
                       {"scene",
                        {{"type", "rack_pinion"},
                         {"pinion", {{"omega_rad_s", -300.0}}},
                         {"rack", {{"velocity_m_s", -7.2}, {"load_N", 5000.0}}}}},
                       {"discretization", {{"particles", "lattice"}, {"spacing_mm", 1.0}}}});
}

TEST(MeshStiffnessCycle, PlanRefusesWhatItCannotMeasure) {
  EXPECT_THROW(plan_mesh_stiffness_cycle(dynamic_job(), 1), InvalidJob);
  json still = dynamic_job();
  still["scene"]["quasi_static"] = true;
  EXPECT_THROW(plan_mesh_stiffness_cycle(still, 4), InvalidJob);
}

}  // namespace
}  // namespace gearsph::study
