#include "server/speed_sweep_study.hpp"

#include <cstdio>

#include "solver/study/speed_sweep.hpp"

namespace gearsph::server {

namespace {

// The lumped model's damping where no SPH run rang down: what the CLI assumes.
constexpr double kFallbackDampingRatio = 0.05;

std::vector<JobIssue> under(const std::string& prefix, const std::vector<JobIssue>& issues) {
  std::vector<JobIssue> out;
  for (const JobIssue& i : issues) out.push_back({prefix + i.pointer, i.message});
  return out;
}

}  // namespace

bool is_speed_sweep(const nlohmann::json& body) {
  return body.is_object() && body.contains("speed_sweep");
}

SpeedSweepStudy plan_speed_sweep_study(const nlohmann::json& body, const Limits& limits) {
  std::vector<JobIssue> issues;
  for (const auto& [key, value] : body.items()) {
    if (key != "name" && key != "speed_sweep") {
      issues.push_back({"/" + key, "is not a field of a speed sweep study (name, speed_sweep)"});
    }
  }
  SpeedSweepStudy out;
  if (body.contains("name")) {
    const nlohmann::json& n = body["name"];
    if (!n.is_string() || n.get<std::string>().empty() || n.get<std::string>().size() > 100) {
      issues.push_back({"/name", "is a string of 1 to 100 characters"});
    } else {
      out.name = n.get<std::string>();
    }
  }
  const nlohmann::json& request = body["speed_sweep"];
  if (!request.is_object()) {
    issues.push_back({"/speed_sweep",
                      "is an object {\"job\": {...}, \"ratios\": [...], \"steady_periods\": 20, "
                      "\"stiffness\": \"iso\"}"});
  } else if (request.value("stiffness", nlohmann::json("iso")) == "measured") {
    issues.push_back({"/speed_sweep/stiffness",
                      "the measured stiffness runs quasi-static checks over a mesh cycle "
                      "(minutes) before the speeds can be chosen, longer than a request may "
                      "take; give \"iso\", or the table an earlier measurement wrote "
                      "(`gearsph study speed-sweep JOB.json --stiffness measured` writes "
                      "stiffness_cycle.json: {\"position\": [...], \"stiffness_N_m\": [...]})"});
  }
  if (!issues.empty()) throw InvalidJob(issues);

  study::SpeedSweepPlan plan;
  try {
    const study::SpeedSweepRequest req = study::read_speed_sweep(request);
    study::SweepLimits sl;
    sl.max_particles = double(limits.max_particles);
    sl.max_steps = double(limits.max_steps);
    sl.max_particle_steps = limits.max_particle_steps;
    sl.max_jobs = static_cast<int>(limits.max_study_jobs);
    plan = study::plan_speed_sweep(req, sl, 30.0, nullptr, 1);
  } catch (const InvalidJob& e) {
    throw InvalidJob(under("/speed_sweep", e.issues));
  }
  if (out.name.empty()) out.name = plan.request.job.value("name", std::string("speed-sweep"));
  for (std::size_t k = 0; k < plan.jobs.size(); ++k) {
    StudyPoint p;
    p.job = plan.jobs[k];
    p.parameters = {{"ratio", plan.request.ratios[k]},
                    {"mesh_frequency_Hz", plan.mesh_frequency_Hz[k]}};
    p.value_index = {k};
    out.points.push_back(std::move(p));
  }
  out.plan = study::plan_document(plan);
  return out;
}

nlohmann::json speed_sweep_report(const nlohmann::json& plan,
                                  const std::vector<nlohmann::json>& summaries) {
  return study::sweep_report(study::plan_from_document(plan), summaries, kFallbackDampingRatio);
}

}  // namespace gearsph::server
