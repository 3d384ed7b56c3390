#include "server/fe_stage_estimate.hpp"

namespace gearsph::server {

namespace {

// Successful jobs looked at, newest first: the checks among them are few.
constexpr std::int64_t kSampleJobs = 50;

}  // namespace

nlohmann::json FeStageEstimate::to_json() const {
  return {{"estimate_s", seconds}, {"basis", basis}, {"checks_measured", checks_measured}};
}

bool runs_fe_check(const nlohmann::json& job) {
  if (!job.is_object() || !job.contains("scene") || !job["scene"].is_object()) return false;
  const nlohmann::json& scene = job["scene"];
  return scene.value("type", "") == "rack_pinion" && scene.value("fe_check", false);
}

FeStageEstimate estimate_fe_stage(JobStore& store) {
  JobQuery q;
  q.statuses = {JobStatus::successful};
  q.limit = kSampleJobs;
  double sum = 0;
  int n = 0;
  for (const JobRecord& j : store.jobs(q).jobs) {
    if (j.fe_check_json.empty()) continue;
    const auto fe = nlohmann::json::parse(j.fe_check_json, nullptr, false);
    // A check that failed early (a tool missing) says nothing of the time.
    if (!fe.is_object() || !fe.contains("wall_s") || !fe["wall_s"].is_number()) continue;
    const std::string status = fe.value("status", "");
    if (status != "compared" && status != "sph_values_missing") continue;
    sum += fe["wall_s"].get<double>();
    ++n;
  }
  FeStageEstimate e;
  if (n > 0 && sum > 0) {
    e.seconds = sum / n;
    e.basis = "measured";
    e.checks_measured = n;
  }
  return e;
}

}  // namespace gearsph::server
