// Parameter studies: POST expands a sweep into jobs; GET follows them and,
// once all are finished, tabulates their summaries (JSON or CSV).
#include <atomic>
#include <exception>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>
#include <variant>

#include "server/problem.hpp"
#include "server/routes.hpp"
#include "server/speed_sweep_study.hpp"
#include "server/study.hpp"
#include "server/submission.hpp"

namespace gearsph::server::routes {

namespace {

constexpr std::size_t kMaxJobName = 120;  // schema: /name maxLength

bool under(const std::string& pointer, const std::string& prefix) {
  return pointer == prefix ||
         (pointer.size() > prefix.size() && pointer.compare(0, prefix.size(), prefix) == 0 &&
          pointer[prefix.size()] == '/');
}

std::optional<nlohmann::json> read_summary(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  auto j = nlohmann::json::parse(s.str(), nullptr, false);
  if (j.is_discarded() || !j.is_object()) return std::nullopt;
  return j;
}

std::string aggregate_status(const std::map<std::string, std::int64_t>& counts,
                             std::int64_t total) {
  auto n = [&](const char* s) {
    const auto it = counts.find(s);
    return it == counts.end() ? std::int64_t(0) : it->second;
  };
  if (n("running") > 0) return "running";
  if (n("accepted") > 0) return n("accepted") == total ? "accepted" : "running";
  if (n("successful") == total) return "successful";
  if (n("dismissed") == total) return "dismissed";
  return "failed";
}

// A finished speed sweep's report (speed_sweep_study.hpp): each speed's
// summary in the plan's order, null for a job that did not succeed.
nlohmann::json sweep_of(Services& s, const nlohmann::json& spec, const JobPage& page) {
  const nlohmann::json& plan = spec["plan"];
  std::vector<nlohmann::json> summaries(plan.at("jobs").size());
  for (const JobRecord& j : page.jobs) {
    const auto k = static_cast<std::size_t>(j.study_index);
    if (j.status != JobStatus::successful || k >= summaries.size()) continue;
    if (auto summary = read_summary(s.job_dir(j) / "summary.json")) summaries[k] = *summary;
  }
  try {
    return speed_sweep_report(plan, summaries);
  } catch (const std::exception& e) {
    return {{"error", std::string("the sweep's report could not be made: ") + e.what()}};
  }
}

struct StudyView {
  nlohmann::json document;
  std::optional<StudyTable> table;  // once every job has finished
};

StudyView view_study(Services& s, const StudyRecord& study) {
  JobQuery q;
  q.study_id = study.id;
  q.limit = std::numeric_limits<std::int64_t>::max();
  const JobPage page = s.store.jobs(q);

  std::map<std::string, std::int64_t> counts{
      {"accepted", 0}, {"running", 0}, {"successful", 0}, {"failed", 0}, {"dismissed", 0}};
  nlohmann::json jobs = nlohmann::json::array();
  double progress = 0.0;
  for (const JobRecord& j : page.jobs) {
    const nlohmann::json st = s.status_of(j);
    ++counts[std::string(to_string(j.status))];
    progress += st["progress"].get<double>();
    jobs.push_back({{"jobID", j.id},
                    {"status", j.status},
                    {"progress", st["progress"]},
                    {"message", j.message},
                    {"parameters", nlohmann::json::parse(j.parameters_json, nullptr, false)},
                    {"href", "/jobs/" + j.id}});
  }
  const auto total = static_cast<std::int64_t>(page.jobs.size());
  const std::string status = aggregate_status(counts, total);

  StudyView v;
  nlohmann::json spec = nlohmann::json::parse(study.spec_json, nullptr, false);
  v.document = {
      {"studyID", study.id},
      {"name", study.name},
      {"created", study.created},
      {"status", status},
      {"progress", total > 0 ? static_cast<int>(progress / double(total)) : 0},
      {"counts", counts},
      {"kind", is_speed_sweep(spec) ? "speed_sweep" : "axes"},
      {"axes", spec.is_object() && spec.contains("axes") ? spec["axes"] : nlohmann::json()},
      {"jobs", jobs}};
  const std::string self = "/studies/" + study.id;
  nlohmann::json links = nlohmann::json::array();
  links.push_back(link(self, "self", "application/json", "this study"));
  if (counts["accepted"] + counts["running"] == 0) {
    std::vector<StudyRow> rows;
    for (const JobRecord& j : page.jobs) {
      StudyRow row;
      row.emplace_back("job", j.study_index + 1);
      row.emplace_back("jobID", j.id);
      row.emplace_back("status", j.status);
      const auto params = nlohmann::json::parse(j.parameters_json, nullptr, false);
      if (params.is_object()) {
        for (const auto& [pointer, value] : params.items()) {
          if (value.is_primitive()) {
            row.emplace_back(pointer, value);
          } else {
            row.emplace_back(pointer, value.dump());
          }
        }
      }
      if (auto summary = read_summary(s.job_dir(j) / "summary.json")) {
        summary->erase("status");  // the job's status is the one that counts
        flatten_scalars(*summary, "", row);
      }
      rows.push_back(std::move(row));
    }
    v.table = study_table(rows);
    v.document["table"] = v.table->rows;
    v.document["columns"] = v.table->columns;
    if (spec.is_object() && spec.contains("plan"))
      v.document["speed_sweep"] = sweep_of(s, spec, page);
    links.push_back(link(self + "?format=csv", "alternate", "text/csv", "the table as CSV"));
  }
  v.document["links"] = links;
  return v;
}

StringResponse no_such_study(const Request& req) {
  return problem::plain(http::status::not_found, "there is no study " + req.param("id"), req.path);
}

}  // namespace

Response create_study(Services& s, Request& req) {
  auto body = read_json_body(req);
  if (auto* error = std::get_if<StringResponse>(&body)) return std::move(*error);
  const nlohmann::json& request = std::get<nlohmann::json>(body);
  auto idem = idempotency_of(req, "studies", request);
  if (auto* error = std::get_if<StringResponse>(&idem)) return std::move(*error);

  StudySpec spec;
  std::vector<StudyPoint> points;
  nlohmann::json stored = request;
  const bool sweep = is_speed_sweep(request);
  try {
    if (sweep) {
      SpeedSweepStudy planned = plan_speed_sweep_study(request, s.config.limits);
      spec.name = planned.name;
      points = std::move(planned.points);
      stored["plan"] = std::move(planned.plan);
    } else {
      spec = parse_study(request, s.config.limits.max_study_jobs);
      points = expand_study(spec);
    }
  } catch (const InvalidJob& e) {
    return refusal_response(
        Refusal{http::status::bad_request, problem::kInvalidJob, "Invalid study", e.issues}, req);
  }
  if (auto full = queue_refusal(s, req, static_cast<std::int64_t>(points.size()))) {
    return std::move(*full);
  }
  const QueueQuota quota = queue_quota(s, req);
  NewStudy study;
  study.id = new_id();
  study.name = !spec.name.empty() ? spec.name
               : spec.base.contains("name") && spec.base["name"].is_string()
                   ? spec.base["name"].get<std::string>()
                   : "study";
  study.spec_json = stored.dump();

  for (std::size_t i = 0; i < points.size(); ++i) {
    StudyPoint& point = points[i];
    if (!sweep && !point.parameters.contains("/name")) {
      const std::string suffix = "-" + std::to_string(i + 1);
      point.job["name"] = study.name.substr(0, kMaxJobName - suffix.size()) + suffix;
    }
  }
  // Every job is checked (its scene built, its stable step found: about a
  // second for the seed paper's case) before any is stored, on as many threads
  // as there are cores: a 16-job study of the seed paper's case was submitted
  // in 18 s on one.
  std::vector<std::variant<NewJob, Refusal>> checked(points.size());
  {
    std::atomic<std::size_t> next{0};
    std::exception_ptr failed;
    std::mutex failed_mutex;
    auto check = [&] {
      for (std::size_t i = next++; i < points.size(); i = next++) {
        try {
          checked[i] = admit_job(s, points[i].job, {});  // as POST /jobs: the deadline bounds it
        } catch (...) {
          const std::lock_guard lock(failed_mutex);
          if (!failed) failed = std::current_exception();
        }
      }
    };
    const std::size_t threads =
        std::min<std::size_t>(points.size(), std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::thread> helpers;
    for (std::size_t t = 1; t < threads; ++t) helpers.emplace_back(check);
    check();
    for (std::thread& t : helpers) t.join();
    if (failed) std::rethrow_exception(failed);
  }
  std::vector<NewJob> jobs;
  for (std::size_t i = 0; i < points.size(); ++i) {
    StudyPoint& point = points[i];
    auto& admitted = checked[i];
    if (auto* refusal = std::get_if<Refusal>(&admitted)) {
      // Point each issue at the axis value that caused it, else into the base.
      Refusal r = *refusal;
      for (JobIssue& issue : r.issues) {
        if (sweep) {
          // The sweep made the job: the speed is what the request chose.
          issue.message =
              "the job at this speed is refused at " + issue.pointer + ": " + issue.message;
          issue.pointer = "/speed_sweep/ratios/" + std::to_string(i);
          continue;
        }
        bool mapped = false;
        for (std::size_t k = 0; k < spec.axes.size() && !mapped; ++k) {
          if (under(issue.pointer, spec.axes[k].pointer)) {
            issue.pointer =
                "/axes/" + std::to_string(k) + "/values/" + std::to_string(point.value_index[k]);
            mapped = true;
          }
        }
        if (!mapped) issue.pointer = "/base" + issue.pointer;
      }
      return refusal_response(r, req, "",
                              "job " + std::to_string(i + 1) + " of " +
                                  std::to_string(points.size()) + " (" + point.parameters.dump() +
                                  "): ");
    }
    NewJob job = std::get<NewJob>(std::move(admitted));
    job.study_id = study.id;
    job.study_index = static_cast<std::int64_t>(i);
    job.parameters_json = point.parameters.dump();
    job.client = quota.client;
    jobs.push_back(std::move(job));
  }

  const SubmitResult r =
      s.store.submit_study(study, jobs, std::get<std::optional<Idempotency>>(idem), quota);
  if (auto full = queue_refusal(s, req, r, static_cast<std::int64_t>(jobs.size()))) {
    return std::move(*full);
  }
  const std::string location = "/studies/" + r.id;
  if (r.kind == SubmitResult::Kind::conflict) return idempotency_conflict(req, location);
  if (r.kind == SubmitResult::Kind::created) {
    for (const NewJob& j : jobs) {
      if (const auto record = s.store.job(j.id)) s.publish_status(*record);
    }
    s.workers.notify();
  }
  const auto record = s.store.study(r.id);
  if (!record) throw std::runtime_error("a stored study is missing: " + r.id);
  return created(r.kind == SubmitResult::Kind::created, location, view_study(s, *record).document);
}

Response study(Services& s, Request& req) {
  if (!is_id(req.param("id"))) return no_such_study(req);
  const auto record = s.store.study(req.param("id"));
  if (!record) return no_such_study(req);
  StudyView v = view_study(s, *record);
  const bool csv = req.query_value("format") == std::optional<std::string>("csv") ||
                   (req.header(http::field::accept).find("text/csv") != std::string::npos);
  if (!csv) return json_response(http::status::ok, v.document);
  if (!v.table) {
    problem::Problem p;
    p.status = http::status::not_found;
    p.type = problem::kResultNotReady;
    p.title = "Result not ready";
    p.detail = "the table is made once every job of the study has finished";
    p.instance = req.path;
    p.extra["counts"] = v.document["counts"];
    return problem::make(p);
  }
  StringResponse res = text_response(http::status::ok, to_csv(*v.table), "text/csv; charset=utf-8");
  res.set(http::field::content_disposition,
          "attachment; filename=\"study-" + record->id + ".csv\"");
  return res;
}

}  // namespace gearsph::server::routes
