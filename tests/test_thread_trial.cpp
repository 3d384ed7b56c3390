// The thread trial (solver/run/thread_trial.hpp): it times a copy, so a run
// whose count it chose is the run that count gives when told from the start.
// Which count wins depends on the machine's load and is not asserted.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "solver/integrate/integrator.hpp"
#include "solver/job/job.hpp"
#include "solver/run/runner.hpp"
#include "solver/run/thread_trial.hpp"

namespace gearsph {
namespace {

using nlohmann::json;

// The plate, short: a few hundred steps of ~300 particles.
const json kPlate = {{"scene", {{"type", "plate"}}},
                     {"discretization", {{"spacing_m", 0.004}}},
                     {"time", {{"end_s", 0.005}}},
                     {"output", {{"frames", 0}, {"history_points", 20}}}};

TEST(ThreadTrial, TimesEveryCountOnACopy) {
  PreparedJob job = prepare_job(kPlate, 1);
  const Simulation before = job.scene.sim;
  const ThreadTrial t = trial_threads(job.scene.sim, 3);
  ASSERT_EQ(t.threads, (std::vector<int>{1, 2, 3}));
  ASSERT_EQ(t.us_per_step.size(), 3u);
  for (const double us : t.us_per_step) {
    EXPECT_TRUE(std::isfinite(us) && us > 0.0) << us;
  }
  EXPECT_NE(std::find(t.threads.begin(), t.threads.end(), t.chosen), t.threads.end());
  // A count is chosen only for beating the smaller ones by the margin.
  const auto chosen = std::find(t.threads.begin(), t.threads.end(), t.chosen) - t.threads.begin();
  for (std::ptrdiff_t k = 0; k < chosen; ++k) {
    EXPECT_LT(t.us_per_step[chosen], (1.0 - kTrialMargin) * t.us_per_step[k]);
  }
  // The scene itself has not moved.
  const Simulation& after = job.scene.sim;
  EXPECT_EQ(after.step, before.step);
  EXPECT_EQ(after.time, before.time);
  EXPECT_EQ(after.particles.x, before.particles.x);
  EXPECT_EQ(after.particles.vy, before.particles.vy);
  EXPECT_EQ(after.threads, before.threads);
}

TEST(ThreadTrial, OneThreadLeavesNothingToTry) {
  PreparedJob job = prepare_job(kPlate, 1);
  const ThreadTrial t = trial_threads(job.scene.sim, 1);
  EXPECT_EQ(t.threads, std::vector<int>{1});
  EXPECT_EQ(t.chosen, 1);
}

TEST(ThreadTrial, ARunAfterATrialIsTheRunOfTheChosenCount) {
  PreparedJob tried = prepare_job(kPlate, 0, 2);
  tried.threads_by = "trial";  // the plate is too short to be tried by default
  tried.trial_threads = 2;
  tried.retrial_every_s = 1e9;  // the first trial only (the next test repeats it)
  const RunResult a = run_job(tried);
  ASSERT_EQ(a.status, "completed") << a.message;
  ASSERT_TRUE(a.summary.contains("thread_trial"));
  EXPECT_EQ(a.summary.at("threads_by"), "trial");
  const int chosen = a.summary.at("threads").get<int>();

  PreparedJob told = prepare_job(kPlate, chosen);
  const RunResult b = run_job(told);
  ASSERT_EQ(b.status, "completed") << b.message;
  EXPECT_EQ(b.summary.at("threads_by"), "caller");
  EXPECT_FALSE(b.summary.contains("thread_trial"));
  // Bit for bit: the same particles, the same history.
  EXPECT_EQ(tried.scene.sim.particles.x, told.scene.sim.particles.x);
  EXPECT_EQ(tried.scene.sim.particles.vy, told.scene.sim.particles.vy);
  EXPECT_EQ(a.history.to_csv(), b.history.to_csv());
  EXPECT_EQ(a.summary.at("max_von_mises_Pa"), b.summary.at("max_von_mises_Pa"));
}

// The trial repeated during the run (after every 64 steps here) times
// copies of the running scene: the run is the run of its switches, bit for
// bit, replayed by setting the counts at the listed steps. Whether and
// where it switches depends on the machine's load and is not asserted.
TEST(ThreadTrial, ARunRepeatingItsTrialIsTheRunOfItsSwitches) {
  PreparedJob tried = prepare_job(kPlate, 0, 2);
  tried.threads_by = "trial";
  tried.trial_threads = 2;
  tried.retrial_every_s = 0.0;
  const RunResult a = run_job(tried);
  ASSERT_EQ(a.status, "completed") << a.message;
  const json& trial = a.summary.at("thread_trial");
  const json& switches = trial.at("switches");
  ASSERT_TRUE(switches.is_array());
  std::int64_t last = 0;
  int threads = trial.at("chosen").get<int>();
  for (const json& w : switches) {
    const std::int64_t step = w.at("step").get<std::int64_t>();
    EXPECT_GT(step, last);
    EXPECT_LE(step, tried.steps);
    EXPECT_NE(w.at("threads").get<int>(), threads) << "a switch to the count it had";
    EXPECT_EQ(w.at("us_per_step").size(), 2u);
    threads = w.at("threads").get<int>();
    last = step;
  }
  EXPECT_EQ(a.summary.at("threads").get<int>(), threads);
  ::testing::Test::RecordProperty("switches", static_cast<int>(switches.size()));

  PreparedJob replay = prepare_job(kPlate, trial.at("chosen").get<int>());
  Simulation& sim = replay.scene.sim;
  integrate::initialise(sim);
  std::size_t next = 0;
  for (std::int64_t s = 1; s <= replay.steps; ++s) {
    if (next < switches.size() && switches[next].at("step").get<std::int64_t>() == s) {
      sim.threads = switches[next++].at("threads").get<int>();
    }
    integrate::step(sim);
  }
  EXPECT_EQ(tried.scene.sim.particles.x, sim.particles.x);
  EXPECT_EQ(tried.scene.sim.particles.vy, sim.particles.vy);
  EXPECT_EQ(tried.scene.sim.particles.sxx, sim.particles.sxx);
}

// The repeated trial moves a run only for a gain past the margin: a spell in
// which both counts step alike leaves it where it is.
TEST(ThreadTrial, ARepeatedTrialSwitchesOnlyPastTheMargin) {
  ThreadTrial again;
  again.threads = {1, 2};
  again.us_per_step = {97.0, 63.0};
  again.chosen = 2;
  EXPECT_EQ(threads_after_retrial(again, 1), 2);  // the spell at the start is over
  EXPECT_EQ(threads_after_retrial(again, 2), 2);
  again.us_per_step = {83.0, 85.0};
  again.chosen = 1;
  EXPECT_EQ(threads_after_retrial(again, 2), 2) << "1 thread is not 5 % faster";
  again.us_per_step = {83.0, 210.0};  // another program holds the second core
  EXPECT_EQ(threads_after_retrial(again, 2), 1);
  again.diverged = true;
  EXPECT_EQ(threads_after_retrial(again, 2), 2);
}

}  // namespace
}  // namespace gearsph
