// Jobs: submit (OGC execute), list, status, dismiss, results.
#include <charconv>
#include <fstream>
#include <sstream>

#include "server/problem.hpp"
#include "server/routes.hpp"
#include "server/static_files.hpp"
#include "server/submission.hpp"

namespace gearsph::server::routes {

namespace {

StringResponse no_such_job(const Request& req) {
  problem::Problem p;
  p.status = http::status::not_found;
  p.type = problem::kNoSuchJob;
  p.title = "No such job";
  p.detail = "there is no job " + (req.params.count("id") ? req.param("id") : std::string());
  p.instance = req.path;
  return problem::make(p);
}

StringResponse bad_parameter(const Request& req, const std::string& detail) {
  problem::Problem p;
  p.status = http::status::bad_request;
  p.type = problem::kInvalidParameter;
  p.title = "Invalid query parameter";
  p.detail = detail;
  p.instance = req.path;
  return problem::make(p);
}

std::optional<std::int64_t> whole_number(const std::string& s) {
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

std::optional<nlohmann::json> read_json_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  auto j = nlohmann::json::parse(s.str(), nullptr, false);
  if (j.is_discarded()) return std::nullopt;
  return j;
}

}  // namespace

Response execute(Services& s, Request& req) {
  if (req.params.count("process") && req.param("process") != kProcessId) {
    problem::Problem p;
    p.status = http::status::not_found;
    p.type = problem::kNoSuchProcess;
    p.title = "No such process";
    p.detail = "the only process is " + std::string(kProcessId);
    p.instance = req.path;
    return problem::make(p);
  }
  auto body = read_json_body(req);
  if (auto* error = std::get_if<StringResponse>(&body)) return std::move(*error);
  const nlohmann::json& request = std::get<nlohmann::json>(body);

  // OGC execute requests wrap the job: {"inputs": {"job": {...}}}.
  const nlohmann::json* job = &request;
  std::string prefix;
  if (request.is_object() && request.contains("inputs")) {
    const auto& inputs = request["inputs"];
    if (!inputs.is_object() || !inputs.contains("job")) {
      problem::Problem p;
      p.status = http::status::bad_request;
      p.type = problem::kInvalidJob;
      p.title = "Invalid job";
      p.detail = "an execute request carries the job as inputs.job";
      p.instance = req.path;
      p.extra["errors"] = {
          {{"pointer", "/inputs/job"}, {"detail", "is required: the job document"}}};
      return problem::make(p);
    }
    job = &inputs["job"];
    prefix = "/inputs/job";
  }

  auto idem = idempotency_of(req, "jobs", request);
  if (auto* error = std::get_if<StringResponse>(&idem)) return std::move(*error);
  auto admitted = admit_job(s, *job);
  if (auto* refusal = std::get_if<Refusal>(&admitted))
    return refusal_response(*refusal, req, prefix);

  const SubmitResult r =
      s.store.submit(std::get<NewJob>(admitted), std::get<std::optional<Idempotency>>(idem));
  const std::string location = "/jobs/" + r.id;
  if (r.kind == SubmitResult::Kind::conflict) return idempotency_conflict(req, location);
  const auto record = s.store.job(r.id);
  if (!record) throw std::runtime_error("a stored job is missing: " + r.id);
  if (r.kind == SubmitResult::Kind::created) {
    s.publish_status(*record);
    s.workers.notify();
  }
  return created(r.kind == SubmitResult::Kind::created, location, s.status_of(*record));
}

Response list_jobs(Services& s, Request& req) {
  JobQuery q;
  for (const std::string& v : req.query_values("status")) {
    std::size_t start = 0;
    while (start <= v.size()) {
      const auto comma = v.find(',', start);
      const std::string one = v.substr(start, comma == std::string::npos ? comma : comma - start);
      if (!one.empty()) {
        if (!is_job_status(one)) {
          return bad_parameter(req, "status '" + one +
                                        "' is not one of accepted, running, successful, failed, "
                                        "dismissed");
        }
        q.statuses.push_back(one);
      }
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }
  if (auto v = req.query_value("limit")) {
    const auto n = whole_number(*v);
    if (!n || *n < 1 || *n > 1000)
      return bad_parameter(req, "limit is a whole number from 1 to 1000");
    q.limit = *n;
  }
  if (auto v = req.query_value("offset")) {
    const auto n = whole_number(*v);
    if (!n || *n < 0) return bad_parameter(req, "offset is a whole number, 0 or more");
    q.offset = *n;
  }
  const JobPage page = s.store.jobs(q);

  nlohmann::json jobs = nlohmann::json::array();
  for (const JobRecord& j : page.jobs) jobs.push_back(s.status_of(j));
  std::string filter;
  if (!q.statuses.empty()) {
    filter = "status=";
    for (std::size_t i = 0; i < q.statuses.size(); ++i) {
      if (i) filter += ',';
      filter += q.statuses[i];
    }
    filter += "&";
  }
  auto page_href = [&](std::int64_t offset) {
    return "/jobs?" + filter + "limit=" + std::to_string(q.limit) +
           "&offset=" + std::to_string(offset);
  };
  nlohmann::json links = nlohmann::json::array();
  links.push_back(link(page_href(q.offset), "self", "application/json", "this page"));
  if (q.offset + q.limit < page.total) {
    links.push_back(link(page_href(q.offset + q.limit), "next", "application/json", "next page"));
  }
  if (q.offset > 0) {
    links.push_back(link(page_href(std::max<std::int64_t>(0, q.offset - q.limit)), "prev",
                         "application/json", "previous page"));
  }
  return json_response(http::status::ok, {{"jobs", jobs},
                                          {"numberMatched", page.total},
                                          {"numberReturned", page.jobs.size()},
                                          {"links", links}});
}

Response job(Services& s, Request& req) {
  if (!is_id(req.param("id"))) return no_such_job(req);
  const auto record = s.store.job(req.param("id"));
  if (!record) return no_such_job(req);
  return json_response(http::status::ok, s.status_of(*record));
}

Response dismiss_job(Services& s, Request& req) {
  if (!is_id(req.param("id"))) return no_such_job(req);
  const std::string& id = req.param("id");
  const auto before = s.store.dismiss(id);
  if (!before) return no_such_job(req);
  s.images.drop_job(id);
  if (before->status == "running") {
    // The worker stops at its next check and then deletes what the run wrote.
    s.workers.cancel(id);
  } else if (!s.workers.live(id)) {
    // Finished, or dismissed before (files left by a run that was stopping,
    // or by a crash): the files go now.
    std::error_code ec;
    std::filesystem::remove_all(s.job_dir(id), ec);
  }
  const auto record = s.store.job(id);
  if (!record) return no_such_job(req);
  if (before->status != "dismissed") s.publish_status(*record);
  return json_response(http::status::ok, s.status_of(*record));
}

Response results(Services& s, Request& req) {
  if (!is_id(req.param("id"))) return no_such_job(req);
  const auto record = s.store.job(req.param("id"));
  if (!record) return no_such_job(req);
  const std::string& id = record->id;
  const auto dir = s.job_dir(id);
  const auto summary = read_json_file(dir / "summary.json");

  if (record->status == "failed") {
    problem::Problem p;
    p.status = http::status::internal_server_error;
    p.type = problem::kJobFailed;
    p.title = "Job failed";
    p.detail = record->message;
    p.instance = req.path;
    p.extra["jobID"] = id;
    if (summary) p.extra["summary"] = *summary;
    return problem::make(p);
  }
  if (record->status != "successful" || !summary) {
    problem::Problem p;
    p.status = http::status::not_found;
    p.type = problem::kResultNotReady;
    p.title = "Result not ready";
    p.detail = record->status == "dismissed" ? "the job was dismissed; it has no results"
               : record->status == "running"
                   ? "the job is running (" +
                         std::to_string(s.status_of(*record)["progress"].get<int>()) + " %)"
               : record->status == "accepted" ? "the job is queued"
                                              : "the job's results are missing";
    p.instance = req.path;
    p.extra["jobID"] = id;
    p.extra["status"] = record->status;
    return problem::make(p);
  }
  nlohmann::json files = nlohmann::json::array();
  nlohmann::json links = nlohmann::json::array();
  links.push_back(link("/jobs/" + id + "/results", "self", "application/json", "these results"));
  links.push_back(link("/jobs/" + id, "up", "application/json", "the job"));
  for (const FileEntry& f : list_files(dir)) {
    const std::string href = "/jobs/" + id + "/files/" + f.name;
    const std::string type = content_type_for(f.name);
    files.push_back({{"name", f.name}, {"bytes", f.bytes}, {"type", type}, {"href", href}});
    links.push_back(link(href, "enclosure", type, f.name));
  }
  return json_response(http::status::ok, {{"jobID", id},
                                          {"status", record->status},
                                          {"summary", *summary},
                                          {"files", files},
                                          {"links", links}});
}

}  // namespace gearsph::server::routes
