// The accuracy map's draws (solver/validation/accuracy_map.hpp): inside the
// space, valid jobs, the same on every call, and pointed teeth left out.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "solver/job/job.hpp"
#include "solver/validation/accuracy_map.hpp"

namespace gearsph {

TEST(AccuracyMap, RadicalInverseIsVanDerCorput) {
  EXPECT_DOUBLE_EQ(validation::radical_inverse(1, 2), 0.5);
  EXPECT_DOUBLE_EQ(validation::radical_inverse(2, 2), 0.25);
  EXPECT_DOUBLE_EQ(validation::radical_inverse(3, 2), 0.75);
  EXPECT_DOUBLE_EQ(validation::radical_inverse(5, 3), 2.0 / 3.0 + 1.0 / 9.0);
}

TEST(AccuracyMap, DrawsAreValidJobsInsideTheSpaceAndRepeat) {
  std::vector<validation::SkippedDraw> skipped;
  const auto cases = validation::accuracy_cases(40, &skipped);
  ASSERT_EQ(cases.size(), 40u);
  const validation::AccuracySpace s;
  std::set<std::string> points;
  std::set<int> teeth;
  for (const auto& c : cases) {
    EXPECT_GE(c.teeth, s.teeth_min);
    EXPECT_LE(c.teeth, s.teeth_max);
    EXPECT_GE(c.module_mm, s.module_min_mm);
    EXPECT_LE(c.module_mm, s.module_max_mm);
    EXPECT_GE(c.pressure_angle_deg, s.pressure_angle_min_deg);
    EXPECT_LE(c.pressure_angle_deg, s.pressure_angle_max_deg);
    EXPECT_GE(c.profile_shift, s.shift_min - 1e-12);
    EXPECT_LE(c.profile_shift, s.shift_max + 1e-12);
    EXPECT_GE(c.rim_modules, s.rim_min_modules - 1e-12);
    EXPECT_LE(c.rim_modules, s.rim_max_modules + 1e-12);
    EXPECT_GE(c.line_load_N_per_mm, s.line_load_min_N_per_mm);
    EXPECT_LE(c.line_load_N_per_mm, s.line_load_max_N_per_mm);
    points.insert(c.contact_point);
    teeth.insert(c.teeth);
    EXPECT_NO_THROW(validate_job(c.job)) << c.job.dump();
    EXPECT_EQ(c.job["scene"]["pinion"]["backlash_mm"], 0.0);  // the FE's geometry
  }
  EXPECT_EQ(points.size(), 3u);
  EXPECT_GT(teeth.size(), 20u);  // spread over the space, not clustered
  for (const auto& d : skipped) EXPECT_FALSE(d.reason.empty()) << d.draw;
  // A smaller map is the start of a larger one.
  const auto five = validation::accuracy_cases(5);
  for (std::size_t k = 0; k < five.size(); ++k) EXPECT_EQ(five[k].job, cases[k].job);
}

// Few teeth with a large positive shift: the flanks meet near the tip.
TEST(AccuracyMap, PointedTeethAreLeftOutWithTheirReason) {
  validation::AccuracySpace s;
  s.teeth_min = s.teeth_max = 8;
  s.shift_min = s.shift_max = 0.8;
  s.pressure_angle_min_deg = s.pressure_angle_max_deg = 20.0;
  std::vector<validation::SkippedDraw> skipped;
  EXPECT_TRUE(validation::accuracy_cases(3, &skipped, s).empty());
  ASSERT_FALSE(skipped.empty());
  for (const auto& d : skipped) {
    EXPECT_TRUE(d.reason.find("tip thickness") != std::string::npos ||
                d.reason.find("pointed") != std::string::npos)
        << d.reason;
  }
}

}  // namespace gearsph
