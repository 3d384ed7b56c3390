#pragma once
// How many OpenMP threads a run gets when nobody said: time a few steps of a
// copy of the scene at each count and keep the fastest. Two threads run the
// paper's gear 1.6-1.7x faster than one on a free 2-core machine, and 2.5x
// slower than one when another program holds the second core (every time
// step waits ~10 times for the thread that is not running;
// docs/speed-accuracy-history.md, Threads). Only a measurement tells the two apart.
//
// The trial steps a copy: the run itself starts from the untouched scene, so
// its results are those of a run told the chosen count from the start.
//
// A trial of ~40 ms that falls in a spell of load would choose for the
// whole run, so a run repeats the trial, on a copy of its current state,
// every kRetrialSeconds (job/job.hpp), and switches to the new choice
// (docs/speed-accuracy-history.md, "Threads"). A run without a switch is still that
// of a run told its count from the start; each switch changes the round-off
// from there on (the threads' sums meet in another order), and the summary
// lists the switches.
#include <vector>

#include "solver/physics/simulation.hpp"

namespace gearsph {

struct ThreadTrial {
  std::vector<int> threads;         // the counts tried, ascending, from 1
  std::vector<double> us_per_step;  // the best of the rounds at each count
  int chosen = 1;
  bool diverged = false;  // the copy diverged: `chosen` is 1 by default, not by timing
};

// Tries 1, 2, 4, ... and `most` threads (most >= 1). A count is kept only if
// it beats every smaller one by kTrialMargin: a second core spent for a
// smaller gain is not worth taking from the rest of the machine.
inline constexpr double kTrialMargin = 0.05;
ThreadTrial trial_threads(const Simulation& sim, int most);

// The count a run at `current` threads takes after repeating the trial:
// the trial's choice if that beats `current` by kTrialMargin, else
// `current` (also after a diverged trial). Within the margin, as in a spell
// where one thread and two step alike, the run stays: a switch there can
// keep a run on fewer threads long past the spell's end (same section).
int threads_after_retrial(const ThreadTrial& again, int current);

}  // namespace gearsph
