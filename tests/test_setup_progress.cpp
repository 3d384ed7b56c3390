// A job's set-up says what it is doing once it has taken a second
// (solver/core/setup_progress.hpp): the particle relaxation, the pairs and
// the stable step report to the sink of the thread that prepares the job,
// throttled, and nothing reaches a thread without one.
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <thread>
#include <vector>

#include "solver/core/setup_progress.hpp"
#include "solver/job/job.hpp"

namespace gearsph {
namespace {

TEST(SetupProgress, QuietForASecondThenThrottledAndScopesNest) {
  std::vector<SetupStatus> heard;
  {
    SetupProgressScope scope([&](const SetupStatus& s) { heard.push_back(s); });
    setup_progress("early", 0.5);
    EXPECT_TRUE(heard.empty());  // a quick set-up says nothing
    std::this_thread::sleep_for(std::chrono::milliseconds(1050));
    setup_progress("late", 1.5);
    ASSERT_EQ(heard.size(), 1u);
    EXPECT_EQ(heard[0].stage, "late");
    EXPECT_EQ(heard[0].fraction, 1.0);  // clamped
    EXPECT_GE(heard[0].elapsed_s, 1.0);
    setup_progress("late", 0.6);
    EXPECT_EQ(heard.size(), 1u);  // within a stage, at most four times a second
    setup_progress("next", 0.0);
    EXPECT_EQ(heard.size(), 2u);  // a new stage at once
    {
      std::vector<SetupStatus> inner;
      SetupProgressScope nested([&](const SetupStatus& s) { inner.push_back(s); }, 0.0);
      setup_progress("inner", 0.1);
      EXPECT_EQ(inner.size(), 1u);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    setup_progress("next", 0.7);
    EXPECT_EQ(heard.size(), 3u);  // the outer sink is back
  }
  setup_progress("nobody", 0.0);  // no sink: nothing, no crash
  EXPECT_EQ(heard.size(), 3u);
}

// The stages of a body-fitted job's set-up reach the sink (no quiet time).
TEST(SetupProgress, ABodyFittedJobReportsItsStages) {
  std::set<std::string> stages;
  double last_fraction = -1.0;
  bool fractions_in_range = true;
  {
    SetupProgressScope scope(
        [&](const SetupStatus& s) {
          stages.insert(s.stage);
          fractions_in_range = fractions_in_range && s.fraction >= 0.0 && s.fraction <= 1.0;
          last_fraction = s.fraction;
        },
        0.0);
    prepare_job({{"scene",
                  {{"type", "plate_with_hole"},
                   {"width_m", 0.02},
                   {"length_m", 0.04},
                   {"hole_radius_m", 0.002}}}},
                1);
  }
  EXPECT_TRUE(stages.count("relaxing particles"));
  EXPECT_TRUE(stages.count("pairing particles"));
  EXPECT_TRUE(stages.count("finding the stable time step"));
  EXPECT_TRUE(fractions_in_range);
}

}  // namespace
}  // namespace gearsph
