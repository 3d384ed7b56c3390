// A root crack in the gear (scene/rack_pinion_crack.hpp): Paris' cycles, the
// equivalent K, where a crack heads, the backup ratio, and the refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "solver/job/job.hpp"
#include "solver/physics/crack_growth.hpp"
#include "solver/scene/rack_pinion_crack.hpp"
#include "tests/support/job_issues.hpp"

namespace gearsph {
namespace {

using geometry::Point;

TEST(Paris, ConstantKGivesTheLengthOverTheRate) {
  const double C = 1e-11, m = 3.0, K = 20e6;  // 20 MPa m^0.5
  const std::vector<double> da{1e-4, 2e-4, 3e-4};
  const double n = physics::paris_cycles(da, {K, K, K, K}, C, m);
  EXPECT_NEAR(n, 6e-4 / (C * std::pow(20.0, m)), 1e-9 * n);
}

TEST(Paris, TrapezoidsConvergeToTheIntegralOfAGrowingK) {
  // K = Y sqrt(a): N = 2 / (C Y^3) (a0^-1/2 - a1^-1/2) for m = 3.
  const double C = 1e-11, m = 3.0, Y = 1e3, a0 = 1e-3, a1 = 5e-3;  // Y in MPa m^0.5 / m^0.5
  const double exact = 2.0 / (C * Y * Y * Y) * (1.0 / std::sqrt(a0) - 1.0 / std::sqrt(a1));
  double last_error = 1.0;
  for (const int steps : {10, 40}) {
    std::vector<double> da(steps, (a1 - a0) / steps), K;
    for (int k = 0; k <= steps; ++k) K.push_back(1e6 * Y * std::sqrt(a0 + k * da[0]));
    const double error = std::abs(physics::paris_cycles(da, K, C, m) / exact - 1.0);
    EXPECT_LT(error, last_error / 10.0) << steps;  // second order: 16 times smaller
    last_error = error;
  }
  EXPECT_LT(last_error, 2e-3);
  EXPECT_TRUE(std::isinf(physics::paris_cycles({1e-4}, {1e6, -1e6}, C, m)));
}

TEST(Paris, EquivalentKIsTheHoopStressAtTheKink) {
  EXPECT_DOUBLE_EQ(physics::equivalent_K(10.0, 0.0), 10.0);
  // Pure mode II: theta_c = -70.53 deg, K_eq = 2 / sqrt(3) |K_II| (Erdogan & Sih).
  EXPECT_NEAR(physics::equivalent_K(0.0, 3.0), 3.0 * 2.0 / std::sqrt(3.0), 1e-12);
}

// A square tooth on a flat rim, its axis along +y: a crack across the root
// runs out at the other flank (tooth); one running down meets the rim's
// bottom edge below the root circle (rim).
TEST(GearCrack, HeadingTellsTheToothFromTheRim) {
  scenes::GearCrackSite site;
  site.outline = {{-0.6, 0.55}, {0.6, 0.55},  {0.6, 0.99},   {0.15, 0.99},
                  {0.15, 1.3},  {-0.15, 1.3}, {-0.15, 0.99}, {-0.6, 0.99}};
  site.centre = {0.0, 0.0};
  site.r_drive = 0.5;
  site.root_radius = 0.98;
  site.tooth_axis = 0.5 * std::numbers::pi;
  site.half_pitch = 0.2;
  EXPECT_EQ(scenes::gear_crack_heading({{-0.16, 1.05}, {-0.1, 1.05}}, site), "tooth");
  EXPECT_EQ(scenes::gear_crack_heading({{-0.16, 1.0}, {-0.1, 0.95}, {-0.1, 0.8}}, site), "rim");
  // Without the rim's bottom edge the ray meets the bore.
  site.outline = {{0.6, 0.99}, {0.15, 0.99}, {0.15, 1.3}, {-0.15, 1.3}, {-0.15, 0.99}};
  EXPECT_EQ(scenes::gear_crack_heading({{-0.1, 0.95}, {-0.1, 0.8}}, site), "rim");
}

nlohmann::json static_gear(const nlohmann::json& pinion_extra = nlohmann::json::object()) {
  nlohmann::json pinion = {{"omega_rad_s", 0.0}};
  pinion.update(pinion_extra);
  return {{"scene",
           {{"type", "rack_pinion"},
            {"quasi_static", true},
            {"contact_point", "hpstc"},
            {"pinion", pinion},
            {"rack", {{"velocity_m_s", 0.0}, {"load_N", 1000.0}}}}},
          {"output", {{"frames", 0}}}};
}

TEST(GearCrack, BackupRatioSetsTheRimsBore) {
  PreparedJob solid = prepare_job(static_gear(), 1);
  const nlohmann::json& p0 = solid.scene.description.at("pinion");
  const double root = p0.at("root_radius_m").get<double>();
  const double depth = p0.at("tip_radius_m").get<double>() - root;
  // Absent: the default rim of one module (4 mm).
  EXPECT_NEAR(p0.at("deformable_from_radius_m").get<double>(), root - 0.004, 1e-12);
  PreparedJob thin = prepare_job(static_gear({{"backup_ratio", 0.5}}), 1);
  EXPECT_NEAR(thin.scene.description.at("pinion").at("deformable_from_radius_m").get<double>(),
              root - 0.5 * depth, 1e-12);
}

TEST(GearCrack, RefusesWhatItCannotModelAtTheField) {
  using testing_support::issues_of;
  const auto no_rim = issues_of(static_gear({{"backup_ratio", 4.0}}));
  ASSERT_EQ(no_rim.size(), 1u);
  EXPECT_EQ(no_rim[0].pointer, "/scene/pinion/backup_ratio");
  EXPECT_NE(no_rim[0].message.find("between 0 and"), std::string::npos) << no_rim[0].message;
  const auto both = issues_of(static_gear({{"backup_ratio", 1.0}, {"rim_depth_mm", 3.0}}));
  ASSERT_EQ(both.size(), 1u);
  EXPECT_EQ(both[0].pointer, "/scene/pinion/backup_ratio");

  auto cracked = [](const nlohmann::json& crack) {
    nlohmann::json job = static_gear();
    job["scene"]["crack"] = crack;
    return job;
  };
  const nlohmann::json ok = {{"fillet_position", 0.5}, {"length_mm", 2.0}};
  EXPECT_TRUE(issues_of(cracked(ok)).empty());
  const auto off = issues_of(cracked({{"fillet_position", 1.5}, {"length_mm", 2.0}}));
  ASSERT_FALSE(off.empty());
  EXPECT_EQ(off[0].pointer, "/scene/crack/fillet_position");
  for (const double length : {0.5, 9.0}) {
    const auto bad = issues_of(cracked({{"fillet_position", 0.5}, {"length_mm", length}}));
    ASSERT_EQ(bad.size(), 1u) << length;
    EXPECT_EQ(bad[0].pointer, "/scene/crack/length_mm");
    EXPECT_NE(bad[0].message.find("s_Fn"), std::string::npos) << bad[0].message;
  }
  const auto step =
      issues_of(cracked({{"fillet_position", 0.5}, {"length_mm", 2.0}, {"increment_mm", 0.1}}));
  ASSERT_EQ(step.size(), 1u);
  EXPECT_EQ(step[0].pointer, "/scene/crack/increment_mm");
  nlohmann::json dynamic = cracked(ok);
  dynamic["scene"]["quasi_static"] = false;
  dynamic["scene"].erase("contact_point");
  const auto dyn = issues_of(dynamic);
  ASSERT_EQ(dyn.size(), 1u);
  EXPECT_EQ(dyn[0].pointer, "/scene/crack");
  nlohmann::json lattice = cracked(ok);
  lattice["discretization"] = {{"particles", "lattice"}};
  const auto lat = issues_of(lattice);
  ASSERT_EQ(lat.size(), 1u);
  EXPECT_EQ(lat[0].pointer, "/discretization/particles");
  nlohmann::json ul = cracked({{"fillet_position", "peak"}, {"length_mm", 2.0}});
  ul["method"] = {{"formulation", "updated_lagrangian"}};
  const auto ul_issues = issues_of(ul);
  ASSERT_FALSE(ul_issues.empty());
  EXPECT_EQ(ul_issues[0].pointer, "/method/formulation");
}

}  // namespace
}  // namespace gearsph
