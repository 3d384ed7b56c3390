#pragma once
// The time loop of a job: steps, samples histories, tracks the peak stress,
// reports progress, honours cancellation and turns a divergence into a
// failed run that keeps everything recorded up to that point.
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "solver/job/job.hpp"
#include "solver/run/history.hpp"

namespace gearsph {

struct Progress {
  std::int64_t step = 0, steps = 0;
  double time_s = 0.0, end_s = 0.0;
  double wall_s = 0.0, eta_s = 0.0;
  double fraction() const { return steps > 0 ? double(step) / double(steps) : 1.0; }
};

struct RunResult {
  std::string status = "completed";  // completed | cancelled | diverged
  std::string message;
  std::int64_t steps_done = 0;
  double wall_s = 0.0;
  History history;
  nlohmann::json summary;
};

// Hooks for writers, progress displays and job services.
class RunObserver {
 public:
  virtual ~RunObserver() = default;
  virtual void on_start(const PreparedJob&) {}
  // After each history sample (the new row is the last one).
  virtual void on_sample(const Simulation&, const History&) {}
  virtual void on_progress(const Progress&) {}
  virtual bool cancelled() { return false; }
  virtual void on_finish(const PreparedJob&, const RunResult&) {}
};

RunResult run_job(PreparedJob& job, RunObserver* observer = nullptr);

}  // namespace gearsph
