#pragma once
// The time loop of a job: steps, samples histories, tracks the peak stress,
// reports progress, honours cancellation and turns a divergence into a
// failed run that keeps everything recorded up to that point.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/diagnostics/history.hpp"
#include "solver/job/job.hpp"

namespace gearsph {

struct Progress {
  std::int64_t step = 0, steps = 0;
  double time_s = 0.0, end_s = 0.0;
  double wall_s = 0.0, eta_s = 0.0;
  double fraction() const { return steps > 0 ? double(step) / double(steps) : 1.0; }
};

// Work that follows the time loop (the FE check of fe/, run by a summary
// addition of run/execute.hpp): its name, the part of it done (0-1) and
// its seconds so far.
struct StageProgress {
  std::string stage;
  double fraction = 0.0, elapsed_s = 0.0;
};

struct RunResult {
  std::string status = "completed";  // completed | cancelled | diverged
  std::string message;
  std::int64_t steps_done = 0;
  std::string ended_early;  // why the run ended before its last step (Scene::ends_early)
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
  // A snapshot of the whole particle state: frame 0 is the initial state,
  // then every PreparedJob::snapshot_every steps and the last step.
  virtual void on_snapshot(const Simulation&, std::int64_t /*frame*/) {}
  virtual void on_progress(const Progress&) {}
  // After the time loop, before summary.json: a stage that follows the run.
  virtual void on_stage(const StageProgress&) {}
  virtual bool cancelled() { return false; }
  virtual void on_finish(const PreparedJob&, const RunResult&) {}
};

// Forwards every hook to several observers, in order.
class ObserverList : public RunObserver {
 public:
  void add(RunObserver* o) {
    if (o) list_.push_back(o);
  }
  void on_start(const PreparedJob& j) override {
    for (auto* o : list_) o->on_start(j);
  }
  void on_sample(const Simulation& s, const History& h) override {
    for (auto* o : list_) o->on_sample(s, h);
  }
  void on_snapshot(const Simulation& s, std::int64_t f) override {
    for (auto* o : list_) o->on_snapshot(s, f);
  }
  void on_progress(const Progress& p) override {
    for (auto* o : list_) o->on_progress(p);
  }
  void on_stage(const StageProgress& s) override {
    for (auto* o : list_) o->on_stage(s);
  }
  bool cancelled() override {
    for (auto* o : list_) {
      if (o->cancelled()) return true;
    }
    return false;
  }
  void on_finish(const PreparedJob& j, const RunResult& r) override {
    for (auto* o : list_) o->on_finish(j, r);
  }

 private:
  std::vector<RunObserver*> list_;
};

RunResult run_job(PreparedJob& job, RunObserver* observer = nullptr);

}  // namespace gearsph
