#pragma once
// How long the FE check of a job (`"fe_check": true`, fe/fe_check.hpp) will
// take, before it runs: the mean of this server's recent checks, else the
// figure measured on a 2-core machine (docs/fe-check.md, Run time). The
// check's meshes are sized by the tooth's fillet radius (default_fillet_sizes),
// so their element counts, and the time, barely depend on the gear's size.
#include <string>

#include <nlohmann/json.hpp>

#include "server/job_store.hpp"
#include "solver/run/runner.hpp"

namespace gearsph::server {

// The example job's check (two meshes, the rack's teeth, the images) took
// 12 to 20 s wall on a loaded 2-core machine: the upper end.
inline constexpr double kFallbackFeCheck_s = 20.0;

struct FeStageEstimate {
  double seconds = kFallbackFeCheck_s;
  std::string basis = "fallback";  // or "measured"
  int checks_measured = 0;
  nlohmann::json to_json() const;
};

// Whether a job document (validated, defaults filled) runs the FE check.
bool runs_fe_check(const nlohmann::json& job);

// From the FE checks that compared among the store's most recent successful
// jobs (their fe_check.wall_s).
FeStageEstimate estimate_fe_stage(JobStore& store);

// The FE stage under way, as last reported (fe/fe_check.cpp, on_stage), and
// the time since: the check reports after each mesh, its clock runs in between.
struct FeStageNow {
  double fraction = 0.0;
  double elapsed_s = 0.0;  // at the report
  double since_report_s = 0.0;
  double sph_wall_s = 0.0;  // the time loop's
};

// A running job's numbers with both stages counted: the FE stage's time, its
// estimate until a part of it is done and its own pace after, is added to
// the wall time and the ETA, and the progress is the share of the total time
// spent, below 100 % until the check is done too. `u` comes with the time
// loop's numbers; `now` is null while the time loop runs. The same for the
// server's workers and for a run under Slurm (docs/api.md, The FE stage).
void count_fe_stage(ProgressUpdate& u, const FeStageEstimate& e, const FeStageNow* now);

// The FE stage's outcome, from a finished run's summary (its fe_comparison
// block, fe/fe_check.hpp) and the run's status (completed | cancelled |
// diverged).
struct FeOutcome {
  bool ok = false;  // compared (perhaps with SPH values missing)
  double wall_s = 0.0;
  nlohmann::json document;  // the job's fe_check member
  std::string sentence;     // for the job's message
};
FeOutcome fe_outcome(const nlohmann::json& summary, const std::string& run_status,
                     const FeStageEstimate& e);

}  // namespace gearsph::server
