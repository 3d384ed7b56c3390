// Jobs: submit (OGC execute), list, status, dismiss, results.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>

#include "server/problem.hpp"
#include "server/routes.hpp"
#include "server/static_files.hpp"
#include "server/submission.hpp"

namespace gearsph::server::routes {

namespace {

std::optional<std::int64_t> whole_number(const std::string& s) {
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

std::optional<double> seconds_number(const std::string& s) {
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v) || v < 0) {
    return std::nullopt;
  }
  return v;
}

// RFC 3339 "2024-05-01T09:30:00.5+02:00" or a date "2024-05-01", as the
// store writes times: UTC with milliseconds, "2024-05-01T07:30:00.500Z".
// A date is its first millisecond, or (end_of_day) its last.
std::optional<std::string> utc_of(const std::string& text, bool end_of_day) {
  int y = 0, mo = 0, d = 0, h = 0, mi = 0, sec = 0, n = 0;
  if (std::sscanf(text.c_str(), "%4d-%2d-%2d%n", &y, &mo, &d, &n) != 3 || n != 10) {
    return std::nullopt;
  }
  double frac = 0;
  int offset_min = 0;
  if (text.size() == 10) {
    if (end_of_day) {
      h = 23;
      mi = 59;
      sec = 59;
      frac = 0.999;
    }
  } else {
    if (text[10] != 'T' && text[10] != 't' && text[10] != ' ') return std::nullopt;
    int m = 0;
    if (std::sscanf(text.c_str() + 11, "%2d:%2d:%2d%n", &h, &mi, &sec, &m) != 3 || m != 8) {
      return std::nullopt;
    }
    std::size_t at = 19;
    if (at < text.size() && text[at] == '.') {
      std::size_t end = at + 1;
      while (end < text.size() && std::isdigit(static_cast<unsigned char>(text[end]))) ++end;
      if (end == at + 1) return std::nullopt;
      frac = std::stod("0" + text.substr(at, end - at));
      at = end;
    }
    const std::string zone = text.substr(at);
    if (zone == "Z" || zone == "z") {
      offset_min = 0;
    } else {
      int oh = 0, om = 0;
      if (zone.size() != 6 || (zone[0] != '+' && zone[0] != '-') ||
          std::sscanf(zone.c_str() + 1, "%2d:%2d", &oh, &om) != 2 || zone[3] != ':') {
        return std::nullopt;
      }
      offset_min = (zone[0] == '+' ? 1 : -1) * (oh * 60 + om);
    }
  }
  if (mo < 1 || mo > 12 || d < 1 || d > 31 || h > 23 || mi > 59 || sec > 60) return std::nullopt;
  std::tm local{};
  local.tm_year = y - 1900;
  local.tm_mon = mo - 1;
  local.tm_mday = d;
  local.tm_hour = h;
  local.tm_min = mi;
  local.tm_sec = sec;
  const double t = double(timegm(&local)) + frac - offset_min * 60.0;
  const auto whole = static_cast<std::time_t>(std::floor(t));
  const int ms = std::clamp(static_cast<int>(std::lround((t - double(whole)) * 1000.0)), 0, 999);
  std::tm utc{};
  gmtime_r(&whole, &utc);
  char out[96];
  std::snprintf(out, sizeof out, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", utc.tm_year + 1900,
                utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec, ms);
  return std::string(out);
}

// OGC datetime: an instant, or "start/end" with ".." (or nothing) for an
// open end. The bounds as the store writes times, "" for open.
std::optional<std::pair<std::string, std::string>> parse_datetime_interval(const std::string& v) {
  const auto slash = v.find('/');
  if (slash == std::string::npos) {
    const auto from = utc_of(v, false), to = utc_of(v, true);
    if (!from || !to) return std::nullopt;
    return std::make_pair(*from, *to);
  }
  const std::string a = v.substr(0, slash), b = v.substr(slash + 1);
  std::pair<std::string, std::string> out;
  if (!a.empty() && a != "..") {
    const auto from = utc_of(a, false);
    if (!from) return std::nullopt;
    out.first = *from;
  }
  if (!b.empty() && b != "..") {
    const auto to = utc_of(b, true);
    if (!to) return std::nullopt;
    out.second = *to;
  }
  if (!out.first.empty() && !out.second.empty() && out.second < out.first) return std::nullopt;
  return out;
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

bool is_json_type(const nlohmann::json& v) {
  if (!v.is_string()) return false;
  const std::string t = v.get<std::string>();
  return t == "application/json" || t.rfind("application/json;", 0) == 0;
}

// The job of an OGC execute request, and the pointer to it in the request
// ("/inputs/job" or "/inputs/job/value"); null with `issues` if the request
// asks for what this process does not offer.
const nlohmann::json* execute_request_job(const nlohmann::json& request, std::string& prefix,
                                          std::vector<JobIssue>& issues) {
  for (const auto& [key, value] : request.items()) {
    if (key == "inputs" || key == "outputs") continue;
    if (key == "response") {
      if (value != "document") {
        issues.push_back({"/response",
                          "only \"document\" is offered: the results are a JSON "
                          "document with the outputs summary, history and results"});
      }
    } else if (key == "subscriber") {
      issues.push_back({"/subscriber",
                        "callbacks are not offered: follow the job's events at "
                        "/jobs/{id}/events instead"});
    } else {
      issues.push_back({"/" + key,
                        "is not a member of an execute request; its members are inputs, "
                        "outputs, response and subscriber"});
    }
  }
  const nlohmann::json& inputs = request["inputs"];
  if (!inputs.is_object() || !inputs.contains("job")) {
    issues.push_back({"/inputs/job", "is required: the job document"});
    return nullptr;
  }
  for (const auto& [key, value] : inputs.items()) {
    if (key != "job") {
      issues.push_back({"/inputs/" + key, "is not an input of this process; its one input is job"});
    }
  }
  if (request.contains("outputs")) {
    const nlohmann::json& outputs = request["outputs"];
    if (!outputs.is_object()) {
      issues.push_back({"/outputs", "is an object of output ids: summary, history, results"});
    } else {
      for (const auto& [key, value] : outputs.items()) {
        if (key != "summary" && key != "history" && key != "results") {
          issues.push_back({"/outputs/" + key,
                            "is not an output of this process; its outputs "
                            "are summary, history and results"});
        }
      }
    }
  }
  const nlohmann::json& job = inputs["job"];
  prefix = "/inputs/job";
  if (job.is_object() && job.contains("href")) {
    issues.push_back({"/inputs/job/href",
                      "a job given by reference is not fetched: send the job "
                      "document itself, as the value"});
    return nullptr;
  }
  if (job.is_object() && job.contains("value")) {  // a qualified value
    for (const auto& [key, value] : job.items()) {
      if (key == "mediaType" && !is_json_type(value)) {
        issues.push_back({"/inputs/job/mediaType", "the job is application/json"});
      } else if (key != "value" && key != "mediaType" && key != "encoding" && key != "schema") {
        issues.push_back({"/inputs/job/" + key,
                          "is not a member of a qualified value; its "
                          "members are value, mediaType, encoding and "
                          "schema"});
      }
    }
    prefix = "/inputs/job/value";
    return issues.empty() ? &job["value"] : nullptr;
  }
  return issues.empty() ? &job : nullptr;
}

}  // namespace

Response execute(Services& s, Request& req) {
  if (req.params.count("process") && req.param("process") != kProcessId)
    return problem::no_such_process(req);
  auto body = read_json_body(req);
  if (auto* error = std::get_if<StringResponse>(&body)) return std::move(*error);
  const nlohmann::json& request = std::get<nlohmann::json>(body);

  // OGC execute requests wrap the job: {"inputs": {"job": ...}}, the job
  // as it is or qualified ({"value": {...}, "mediaType": "application/json"}).
  const nlohmann::json* job = &request;
  std::string prefix;
  if (request.is_object() && request.contains("inputs")) {
    std::vector<JobIssue> issues;
    job = execute_request_job(request, prefix, issues);
    if (!issues.empty()) {
      return refusal_response(Refusal{http::status::bad_request, problem::kInvalidJob,
                                      "Invalid execute request", issues},
                              req);
    }
  }

  auto idem = idempotency_of(req, "jobs", request);
  if (auto* error = std::get_if<StringResponse>(&idem)) return std::move(*error);
  if (auto full = queue_refusal(s, req, 1)) return std::move(*full);
  // Bounded by the build deadline alone: a submission changes the store,
  // and a client that half-closes its side after sending (pipelining,
  // `nc -N`) still waits for its answer, which a peek cannot tell from one
  // that hung up. Previews, which change nothing, also stop on a hang-up.
  auto admitted = admit_job(s, *job, {});
  if (auto* refusal = std::get_if<Refusal>(&admitted))
    return refusal_response(*refusal, req, prefix);

  const QueueQuota quota = queue_quota(s, req);
  std::get<NewJob>(admitted).client = quota.client;
  const SubmitResult r =
      s.store.submit(std::get<NewJob>(admitted), std::get<std::optional<Idempotency>>(idem), quota);
  if (auto full = queue_refusal(s, req, r, 1)) return std::move(*full);
  const std::string location = "/jobs/" + r.id;
  if (r.kind == SubmitResult::Kind::conflict) return idempotency_conflict(req, location);
  const auto record = s.store.job(r.id);
  if (!record) throw std::runtime_error("a stored job is missing: " + r.id);
  if (r.kind == SubmitResult::Kind::created) {
    s.publish_status(*record);
    s.workers.notify();
  }
  StringResponse res =
      created(r.kind == SubmitResult::Kind::created, location, s.status_of(*record));
  // Every job runs asynchronously: a client preferring that is told it got
  // it (RFC 7240, 3; OGC API - Processes 1.0, 7.11.2.3); one asking to wait
  // is not, and reads the status document instead.
  const std::string prefer = req.header(http::field::prefer);
  if (prefer.find("respond-async") != std::string::npos) {
    res.set(http::field::preference_applied, "respond-async");
  }
  return res;
}

Response list_jobs(Services& s, Request& req) {
  static const std::vector<std::string> known = {"status",      "limit",       "offset",
                                                 "processID",   "type",        "datetime",
                                                 "minDuration", "maxDuration", "f"};
  for (const auto& [name, value] : req.query) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      return problem::invalid_parameter(
          req, "'" + name +
                   "' is not a parameter of the job list; its parameters are "
                   "status, limit, offset, processID, type, datetime, "
                   "minDuration, maxDuration and f");
    }
  }
  if (auto f = req.query_value("f"); f && *f != "json") {
    return problem::invalid_parameter(req, "the job list is JSON: f=json, not f=" + *f);
  }
  JobQuery q;
  // Values of a parameter given several times or as a comma list.
  auto values_of = [&](const char* name) {
    std::vector<std::string> out;
    for (const std::string& v : req.query_values(name)) {
      std::size_t start = 0;
      while (start <= v.size()) {
        const auto comma = v.find(',', start);
        std::string one = v.substr(start, comma == std::string::npos ? comma : comma - start);
        if (!one.empty()) out.push_back(std::move(one));
        if (comma == std::string::npos) break;
        start = comma + 1;
      }
    }
    return out;
  };
  for (const std::string& one : values_of("status")) {
    const auto status = parse_job_status(one);
    if (!status) {
      return problem::invalid_parameter(
          req, "status '" + one +
                   "' is not one of accepted, running, successful, failed, "
                   "dismissed");
    }
    q.statuses.push_back(*status);
  }
  if (auto v = req.query_value("limit")) {
    const auto n = whole_number(*v);
    if (!n || *n < 1 || *n > 1000)
      return problem::invalid_parameter(req, "limit is a whole number from 1 to 1000");
    q.limit = *n;
  }
  if (auto v = req.query_value("offset")) {
    const auto n = whole_number(*v);
    if (!n || *n < 0) return problem::invalid_parameter(req, "offset is a whole number, 0 or more");
    q.offset = *n;
  }
  // Every job is of the one process, of type "process": another asks for none.
  const auto processes = values_of("processID");
  const auto types = values_of("type");
  const bool none =
      (!processes.empty() &&
       std::find(processes.begin(), processes.end(), kProcessId) == processes.end()) ||
      (!types.empty() && std::find(types.begin(), types.end(), "process") == types.end());
  if (auto v = req.query_value("datetime")) {
    const auto interval = parse_datetime_interval(*v);
    if (!interval) {
      return problem::invalid_parameter(
          req,
          "datetime is an RFC 3339 date-time (2024-05-01T09:30:00Z), a "
          "date, or an interval of them with .. for an open end "
          "(2024-05-01/.., ../2024-05-02T12:00:00Z)");
    }
    q.created_from = interval->first;
    q.created_to = interval->second;
  }
  for (const char* name : {"minDuration", "maxDuration"}) {
    if (auto v = req.query_value(name)) {
      const auto seconds = seconds_number(*v);
      if (!seconds)
        return problem::invalid_parameter(req, std::string(name) + " is seconds, 0 or more");
      (std::string(name) == "minDuration" ? q.min_wall_s : q.max_wall_s) = *seconds;
    }
  }
  JobPage page;
  if (!none) page = s.store.jobs(q);

  nlohmann::json jobs = nlohmann::json::array();
  for (const JobRecord& j : page.jobs) jobs.push_back(s.status_of(j));
  // The pages' links keep the filters.
  std::string filter;
  for (const auto& [name, value] : req.query) {
    if (name == "limit" || name == "offset") continue;
    filter += percent_encode(name) + "=" + percent_encode(value) + "&";
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
  if (!is_id(req.param("id"))) return problem::no_such_job(req);
  const auto record = s.store.job(req.param("id"));
  if (!record) return problem::no_such_job(req);
  return json_response(http::status::ok, s.status_of(*record));
}

Response dismiss_job(Services& s, Request& req) {
  if (!is_id(req.param("id"))) return problem::no_such_job(req);
  const std::string& id = req.param("id");
  const auto before = s.store.dismiss(id);
  if (!before) return problem::no_such_job(req);
  s.images.drop_job(id);
  if (before->status == JobStatus::running) {
    // The worker stops at its next check and then deletes what the run wrote.
    s.workers.cancel(id);
  } else {
    // Finished, or dismissed before (files left by a run that was stopping,
    // or by a crash): the files go now. A run still stopping writes only in
    // its own attempt directory and removes that itself.
    std::error_code ec;
    std::filesystem::remove_all(s.jobs_dir / id, ec);
    if (!s.workers.live(id)) discard_attempts(s.jobs_dir, id);
  }
  const auto record = s.store.job(id);
  if (!record) return problem::no_such_job(req);
  if (before->status != JobStatus::dismissed) s.publish_status(*record);
  return json_response(http::status::ok, s.status_of(*record));
}

Response results(Services& s, Request& req) {
  if (!is_id(req.param("id"))) return problem::no_such_job(req);
  const auto record = s.store.job(req.param("id"));
  if (!record) return problem::no_such_job(req);
  const std::string& id = record->id;
  const auto dir = s.job_dir(*record);
  const auto summary = read_json_file(dir / "summary.json");

  if (record->status == JobStatus::failed) {
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
  if (record->status != JobStatus::successful || !summary) {
    problem::Problem p;
    p.status = http::status::not_found;
    p.type = problem::kResultNotReady;
    p.title = "Result not ready";
    p.detail = record->status == JobStatus::dismissed ? "the job was dismissed; it has no results"
               : record->status == JobStatus::running
                   ? "the job is running (" +
                         std::to_string(s.status_of(*record)["progress"].get<int>()) + " %)"
               : record->status == JobStatus::accepted ? "the job is queued"
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
  // OGC API - Processes: the outputs by the ids the process description
  // declares, summary as a value, history and results as links; then the
  // job's every file.
  nlohmann::json doc = {{"summary", *summary}};
  for (const auto& [output, file] :
       {std::pair<const char*, const char*>{"history", "history.csv"}, {"results", "results.h5"}}) {
    if (find_listed_file(dir, file)) {
      doc[output] =
          link("/jobs/" + id + "/files/" + file, "enclosure", content_type_for(file), file);
    }
  }
  doc["jobID"] = id;
  doc["status"] = record->status;
  doc["files"] = files;
  doc["links"] = links;
  return json_response(http::status::ok, doc);
}

}  // namespace gearsph::server::routes
