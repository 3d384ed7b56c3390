#pragma once
// summary.json: the numbers a user or a pipeline reads first.
#include <cstdint>

#include <nlohmann/json.hpp>

#include "solver/core/pass_times.hpp"
#include "solver/job/job.hpp"

namespace gearsph {

struct RunResult;

// The largest von Mises stress seen at any step, with when and where.
struct PeakTracker {
  double von_mises = 0.0;
  double time = 0.0;
  long particle = -1;
  double x = 0.0, y = 0.0;
  void update(const Simulation& sim);
};

nlohmann::json make_summary(const PreparedJob& job, const RunResult& result,
                            const PeakTracker& peak);

// The summary's `timing`: each pass of the step by name, its seconds over
// the run's `steps` (from the timed steps) and its share of the step.
nlohmann::json pass_timing(const PassTimes& times, std::int64_t steps);

}  // namespace gearsph
