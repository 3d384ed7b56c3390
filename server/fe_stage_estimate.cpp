#include "server/fe_stage_estimate.hpp"

#include <algorithm>
#include <cstdio>

namespace gearsph::server {

namespace {

// Successful jobs looked at, newest first: the checks among them are few.
constexpr std::int64_t kSampleJobs = 50;

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

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

void count_fe_stage(ProgressUpdate& u, const FeStageEstimate& e, const FeStageNow* now) {
  nlohmann::json fe = e.to_json();
  double fe_left = e.seconds;
  if (now) {
    const double elapsed = now->elapsed_s + now->since_report_s;
    // Until a part is done, the estimate; then the pace of the parts done.
    fe_left = now->fraction > 0 ? std::max(0.0, now->elapsed_s / now->fraction - elapsed)
                                : std::max(0.0, e.seconds - elapsed);
    u.stage = "fe_check";
    u.wall_s = now->sph_wall_s + elapsed;
    u.eta_s = fe_left;
    fe["status"] = "running";
    fe["fraction"] = now->fraction;
    fe["wall_s"] = elapsed;
  } else {
    u.eta_s += fe_left;
    fe["status"] = "pending";
  }
  fe["eta_s"] = fe_left;
  const double total = u.wall_s + u.eta_s;
  u.progress = total > 0 ? std::clamp(static_cast<int>(100.0 * u.wall_s / total), 0, 99) : 0;
  u.fe_check_json = fe.dump();
}

FeOutcome fe_outcome(const nlohmann::json& summary, const std::string& run_status,
                     const FeStageEstimate& e) {
  FeOutcome o;
  const nlohmann::json* block = summary.is_object() && summary.contains("fe_comparison")
                                    ? &summary["fe_comparison"]
                                    : nullptr;
  std::string status = "not_run", said;
  if (block && block->is_object()) {
    status = block->value("status", "failed");
    said = block->value("message", "");
    if (block->contains("wall_s") && (*block)["wall_s"].is_number()) {
      o.wall_s = (*block)["wall_s"].get<double>();
    }
  } else if (run_status == "completed") {
    status = "failed";
    said = "the FE check left no outcome in the summary";
  } else {
    said = "the SPH run did not complete (" + run_status + ")";
  }
  o.ok = status == "compared" || status == "sph_values_missing";
  o.document = {{"status", status},
                {"message", said},
                {"wall_s", o.wall_s},
                {"estimate_s", e.seconds},
                {"basis", e.basis}};
  if (o.ok) {
    o.sentence = "the FE check compared in " + fixed(o.wall_s, 2) + " s";
  } else {
    // The check's own words may say it already (fe/fe_check.cpp): not twice.
    const std::string lead = "the FE check failed: ";
    const std::string words = said.rfind(lead, 0) == 0 ? said.substr(lead.size()) : said;
    o.sentence = "the FE check " + std::string(status == "failed" ? "failed" : status) +
                 (words.empty() ? "" : ": " + words);
  }
  return o;
}

}  // namespace gearsph::server
