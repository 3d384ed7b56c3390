#include "server/documents.hpp"

#include <algorithm>
#include <cstdio>
#include <random>

#include "server/fe_stage_estimate.hpp"

namespace gearsph::server {

std::string new_id() {
  static thread_local std::random_device device;
  std::uint64_t hi = (std::uint64_t(device()) << 32) | device();
  std::uint64_t lo = (std::uint64_t(device()) << 32) | device();
  hi = (hi & ~0xF000ull) | 0x4000ull;              // version 4
  lo = (lo & ~(0xC0ull << 56)) | (0x80ull << 56);  // RFC 4122 variant
  char out[37];
  std::snprintf(out, sizeof out, "%08llx-%04llx-%04llx-%04llx-%012llx",
                static_cast<unsigned long long>(hi >> 32),
                static_cast<unsigned long long>((hi >> 16) & 0xFFFF),
                static_cast<unsigned long long>(hi & 0xFFFF),
                static_cast<unsigned long long>(lo >> 48),
                static_cast<unsigned long long>(lo & 0xFFFFFFFFFFFFull));
  return out;
}

bool is_id(std::string_view s) {
  if (s.size() != 36) return false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (i == 8 || i == 13 || i == 18 || i == 23) {
      if (c != '-') return false;
    } else if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) {
      return false;
    }
  }
  return true;
}

nlohmann::json link(const std::string& href, const std::string& rel, const std::string& type,
                    const std::string& title) {
  nlohmann::json l = {{"href", href}, {"rel", rel}, {"type", type}};
  if (!title.empty()) l["title"] = title;
  return l;
}

int percent(std::int64_t step, std::int64_t steps) {
  if (steps <= 0) return 0;
  if (step >= steps) return 100;
  return std::clamp(static_cast<int>(100.0 * double(step) / double(steps)), 0, 99);
}

nlohmann::json fe_check_member(const JobRecord& job, const std::string& fe_check_json) {
  if (!fe_check_json.empty()) {
    auto fe = nlohmann::json::parse(fe_check_json, nullptr, false);
    if (fe.is_object()) return fe;
  }
  // Queued or running, with nothing reported yet: whether it will run the
  // check. (A job that ended without a report, run by an outside
  // scheduler, says nothing rather than "pending" forever.)
  const bool ahead = job.status == JobStatus::accepted || job.status == JobStatus::running;
  if (ahead && job.job_json.find("\"fe_check\"") != std::string::npos &&
      runs_fe_check(nlohmann::json::parse(job.job_json, nullptr, false))) {
    return {{"status", "pending"}};
  }
  return nullptr;
}

nlohmann::json stage_wall(double wall_s, const nlohmann::json& fe_check) {
  if (!fe_check.is_object() || !fe_check.contains("wall_s") || !fe_check["wall_s"].is_number()) {
    return {{"sph", wall_s}, {"fe_check", fe_check.is_object() ? nlohmann::json(0.0) : nullptr}};
  }
  const double fe = fe_check["wall_s"].get<double>();
  return {{"sph", std::max(0.0, wall_s - fe)}, {"fe_check", fe}};
}

nlohmann::json status_document(const JobRecord& job, const std::optional<ProgressUpdate>& live) {
  nlohmann::json d;
  d["jobID"] = job.id;
  d["processID"] = kProcessId;
  d["type"] = "process";
  d["name"] = job.name;
  d["status"] = job.status;
  d["message"] = job.message;
  std::int64_t step = job.step;
  double simulated = job.simulated_s, wall = job.wall_s, eta = job.eta_s;
  int progress = job.progress;
  std::string stage = job.stage, fe_check = job.fe_check_json;
  const bool running = job.status == JobStatus::running;
  if (live && running) {
    step = live->step;
    simulated = live->simulated_s;
    wall = live->wall_s;
    eta = live->eta_s;
    progress = live->progress;
    stage = live->stage;
    if (!live->fe_check_json.empty()) fe_check = live->fe_check_json;
  }
  d["progress"] = progress;
  d["stage"] = running && !stage.empty() ? nlohmann::json(stage) : nlohmann::json(nullptr);
  d["step"] = step;
  d["steps"] = job.steps;
  d["particles"] = job.particles;
  d["simulated_s"] = simulated;
  d["end_s"] = job.end_s;
  d["wall_s"] = wall;
  d["fe_check"] = fe_check_member(job, fe_check);
  d["stage_wall_s"] = stage_wall(wall, d["fe_check"]);
  if (running) {
    d["eta_s"] = eta;
  } else {
    d["eta_s"] = nullptr;
  }
  d["attempts"] = job.attempts;
  d["created"] = job.created;
  d["started"] = job.started.empty() ? nlohmann::json(nullptr) : nlohmann::json(job.started);
  d["finished"] = job.finished.empty() ? nlohmann::json(nullptr) : nlohmann::json(job.finished);
  d["updated"] = job.updated;
  if (!job.study_id.empty()) {
    d["studyID"] = job.study_id;
    d["parameters"] = nlohmann::json::parse(job.parameters_json, nullptr, false);
  }
  const std::string self = "/jobs/" + job.id;
  nlohmann::json links = nlohmann::json::array();
  links.push_back(link(self, "self", "application/json", "this job's status"));
  links.push_back(link(self + "/events", "monitor", "text/event-stream", "progress events"));
  if (job.status == JobStatus::successful || job.status == JobStatus::failed) {
    links.push_back(link(self + "/results", "http://www.opengis.net/def/rel/ogc/1.0/results",
                         "application/json", "results"));
  }
  if (!job.study_id.empty()) {
    links.push_back(link("/studies/" + job.study_id, "up", "application/json", "the study"));
  }
  d["links"] = links;
  return d;
}

}  // namespace gearsph::server
