#include "solver/run/thread_trial.hpp"

#include <algorithm>
#include <chrono>
#include <limits>

#include "solver/integrate/integrator.hpp"

namespace gearsph {

namespace {

using Clock = std::chrono::steady_clock;

// Each timing runs whole steps for at least this long: ~40-70 steps of the
// paper's gear, long against a thread's wake-up, short against the run.
constexpr double kSliceSeconds = 0.005;
constexpr int kMinSliceSteps = 8;
// Rounds over the counts, alternating, keeping each count's best: a spell
// of load on the machine then spoils one round, not the choice.
constexpr int kRounds = 4;
// Steps at each count before timing: the counts' cuts of the rows are
// planned and the OpenMP team exists.
constexpr int kWarmSteps = 4;

double seconds_per_step(Simulation& sim) {
  const auto start = Clock::now();
  int steps = 0;
  double elapsed = 0.0;
  while (steps < kMinSliceSteps || elapsed < kSliceSeconds) {
    integrate::step(sim);
    ++steps;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  }
  return elapsed / steps;
}

}  // namespace

ThreadTrial trial_threads(const Simulation& sim, int most) {
  ThreadTrial trial;
  most = std::max(1, most);
  for (int t = 1; t < most; t *= 2) trial.threads.push_back(t);
  trial.threads.push_back(most);
  trial.us_per_step.assign(trial.threads.size(), std::numeric_limits<double>::infinity());
  if (most == 1) return trial;

  Simulation copy = sim;
  try {
    copy.threads = most;
    integrate::initialise(copy);
    for (const int t : trial.threads) {
      copy.threads = t;
      for (int s = 0; s < kWarmSteps; ++s) integrate::step(copy);
    }
    for (int round = 0; round < kRounds; ++round) {
      for (std::size_t k = 0; k < trial.threads.size(); ++k) {
        copy.threads = trial.threads[k];
        trial.us_per_step[k] = std::min(trial.us_per_step[k], 1e6 * seconds_per_step(copy));
      }
    }
  } catch (const DivergenceError&) {
    // The run will meet the same divergence and report it; one thread is as
    // good as any for that.
    trial.chosen = 1;
    trial.diverged = true;
    return trial;
  }
  // The largest count that beats every smaller one by the margin.
  double fastest_smaller = trial.us_per_step[0];
  for (std::size_t k = 1; k < trial.threads.size(); ++k) {
    if (trial.us_per_step[k] < (1.0 - kTrialMargin) * fastest_smaller) {
      trial.chosen = trial.threads[k];
    }
    fastest_smaller = std::min(fastest_smaller, trial.us_per_step[k]);
  }
  return trial;
}

int threads_after_retrial(const ThreadTrial& again, int current) {
  if (again.diverged || again.chosen == current) return current;
  auto us_at = [&](int threads) {
    const auto k = std::find(again.threads.begin(), again.threads.end(), threads);
    return k == again.threads.end() ? std::numeric_limits<double>::infinity()
                                    : again.us_per_step[k - again.threads.begin()];
  };
  return us_at(again.chosen) < (1.0 - kTrialMargin) * us_at(current) ? again.chosen : current;
}

}  // namespace gearsph
