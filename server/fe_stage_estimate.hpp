#pragma once
// How long the FE check of a job (`"fe_check": true`, fe/fe_check.hpp) will
// take, before it runs: the mean of this server's recent checks, else the
// figure measured on a 2-core machine (docs/fe-check.md, Run time). The
// check's meshes are sized by the tooth's fillet radius (default_fillet_sizes),
// so their element counts, and the time, barely depend on the gear's size.
#include <string>

#include <nlohmann/json.hpp>

#include "server/job_store.hpp"

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

}  // namespace gearsph::server
