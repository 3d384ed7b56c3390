#include "server/submission.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <vector>

#include "server/documents.hpp"
#include "server/job_limits.hpp"
#include "server/problem.hpp"
#include "server/router.hpp"
#include "solver/core/json_schema.hpp"
#include "solver/job/job.hpp"
#include "solver/job/job_size.hpp"

namespace gearsph::server {

namespace {

// Jobs nest a few levels; anything far deeper is refused before parsing,
// so no recursive walk over the document can exhaust the stack.
constexpr int kMaxJsonDepth = 64;

bool nested_too_deep(std::string_view text) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      if (++depth > kMaxJsonDepth) return true;
    } else if (c == '}' || c == ']') {
      --depth;
    }
  }
  return false;
}

// Follows the parse and, when it fails, knows the JSON pointer of the value
// it was reading: for numbers too large for a double, which are valid JSON
// but have no value here.
class PointerAtError : public nlohmann::json_sax<nlohmann::json> {
 public:
  std::string pointer;  // of the value at the error
  std::string token;    // the text of that value

  bool null() override { return value_done(); }
  bool boolean(bool) override { return value_done(); }
  bool number_integer(number_integer_t) override { return value_done(); }
  bool number_unsigned(number_unsigned_t) override { return value_done(); }
  bool number_float(number_float_t, const string_t&) override { return value_done(); }
  bool string(string_t&) override { return value_done(); }
  bool binary(binary_t&) override { return value_done(); }
  bool start_object(std::size_t) override {
    stack_.push_back({false, 0, {}});
    return true;
  }
  bool key(string_t& k) override {
    stack_.back().key = k;
    return true;
  }
  bool end_object() override {
    stack_.pop_back();
    return value_done();
  }
  bool start_array(std::size_t) override {
    stack_.push_back({true, 0, {}});
    return true;
  }
  bool end_array() override {
    stack_.pop_back();
    return value_done();
  }
  bool parse_error(std::size_t, const std::string& last_token,
                   const nlohmann::detail::exception&) override {
    for (const Frame& f : stack_) {
      pointer.push_back('/');
      pointer.append(f.array ? std::to_string(f.index) : jsonschema::escape_pointer_token(f.key));
    }
    token = last_token;
    return false;
  }

 private:
  struct Frame {
    bool array;
    std::size_t index;
    std::string key;
  };
  bool value_done() {
    if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
    return true;
  }
  std::vector<Frame> stack_;
};

bool is_json_media_type(std::string_view type) {
  const auto semi = type.find(';');
  std::string t(type.substr(0, semi));
  while (!t.empty() && t.back() == ' ') t.pop_back();
  for (char& c : t) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return t == "application/json" || (t.size() > 5 && t.rfind("application/", 0) == 0 &&
                                     t.compare(t.size() - 5, 5, "+json") == 0);
}

}  // namespace

std::variant<nlohmann::json, StringResponse> read_json_body(const Request& req) {
  const std::string type = req.header(http::field::content_type);
  if (!is_json_media_type(type)) {
    return problem::plain(http::status::unsupported_media_type,
                          type.empty()
                              ? "send the job as JSON with \"Content-Type: application/json\""
                              : "the body is " + type +
                                    "; send the job as JSON with \"Content-Type: "
                                    "application/json\"",
                          req.path);
  }
  const std::string& body = req.msg.body();
  problem::Problem p;
  p.status = http::status::bad_request;
  p.type = problem::kMalformedJson;
  p.title = "Malformed JSON";
  p.instance = req.path;
  // JSON text has no raw NUL (RFC 8259 section 7: control characters are
  // escaped); the parser would stop at one and read the rest as absent.
  if (const auto nul = body.find('\0'); nul != std::string::npos) {
    p.detail = "the body holds a NUL byte at offset " + std::to_string(nul) +
               "; JSON text escapes control characters (\\u0000)";
    return problem::make(p);
  }
  if (nested_too_deep(body)) {
    p.detail = "the body nests objects or arrays more than " + std::to_string(kMaxJsonDepth) +
               " levels deep";
    return problem::make(p);
  }
  try {
    return nlohmann::json::parse(body);
  } catch (const nlohmann::json::parse_error& e) {
    std::string what = e.what();
    const auto bracket = what.find("] ");
    if (what.rfind("[json.exception", 0) == 0 && bracket != std::string::npos) {
      what = what.substr(bracket + 2);
    }
    p.detail = "the body is not valid JSON: " + what;
    return problem::make(p);
  } catch (const nlohmann::json::out_of_range&) {
    // A number beyond the range of a double (about 1.8e308): valid JSON,
    // but no value here can hold it. Where is it?
    PointerAtError where;
    nlohmann::json::sax_parse(body, &where);
    std::string token = where.token;
    if (token.size() > 40) token = token.substr(0, 37) + "...";
    const std::string detail =
        "the number " + token + " is out of range: numbers must lie within +-1.8e308 (a double)";
    p.type = problem::kNumberOutOfRange;
    p.title = "Number out of range";
    p.detail = detail;
    p.extra["errors"] = {{{"pointer", where.pointer}, {"detail", detail}}};
    return problem::make(p);
  }
}

std::variant<std::optional<Idempotency>, StringResponse> idempotency_of(
    const Request& req, const std::string& scope, const nlohmann::json& body) {
  if (!req.msg.count("Idempotency-Key")) return std::optional<Idempotency>{};
  const std::string key(req.msg["Idempotency-Key"]);
  const bool ok = !key.empty() && key.size() <= 255 &&
                  std::all_of(key.begin(), key.end(), [](char c) { return c > 0x20 && c < 0x7f; });
  if (!ok) {
    problem::Problem p;
    p.status = http::status::bad_request;
    p.type = problem::kInvalidParameter;
    p.title = "Invalid Idempotency-Key";
    p.detail = "an Idempotency-Key has 1 to 255 visible ASCII characters";
    p.instance = req.path;
    return problem::make(p);
  }
  // Canonical form: the same JSON with other white space or key order is the same request.
  return std::optional<Idempotency>(Idempotency{scope, key, body.dump()});
}

// The FE check after the run needs gmsh and CalculiX here (or on the
// workers, which run the same build): refused now, not after the run.
std::optional<Refusal> fe_refusal(const Services& services, const nlohmann::json& job) {
  if (!job.at("scene").value("fe_check", false)) return std::nullopt;
  const std::string why = services.config.fe_check_unavailable
                              ? services.config.fe_check_unavailable()
                              : "FE unavailable: this service was built without the FE layer";
  if (why.empty()) return std::nullopt;
  return Refusal{http::status::not_implemented,
                 problem::kFeUnavailable,
                 "FE check unavailable",
                 {{"/scene/fe_check", why}}};
}

namespace {

Refusal too_large(std::vector<JobIssue> over, const JobEstimate& e, const JobSize& size,
                  const Limits& limits) {
  Refusal r{http::status::unprocessable_entity, problem::kJobTooLarge, "Job too large",
            std::move(over)};
  r.extra["estimate"] = e.to_json();
  r.extra["estimate"]["basis"] = size.to_json();
  r.extra["limits"] = limits_json(limits);
  return r;
}

NewJob new_job(const nlohmann::json& job, const JobEstimate& e, double end_s) {
  NewJob out;
  out.id = new_id();
  out.name = job.at("name").get<std::string>();
  out.job_json = job.dump();
  out.particles = e.particles;
  out.steps = e.steps;
  out.end_s = end_s;
  return out;
}

}  // namespace

std::variant<NewJob, Refusal> admit_job(const Services& services, const nlohmann::json& raw,
                                        const std::function<bool()>& gone) {
  const Limits& limits = services.config.limits;
  try {
    const nlohmann::json job = validate_job(raw);
    if (auto refused = fe_refusal(services, job)) return *refused;
    // Sized first, from coarse copies (milliseconds), so that a job too
    // large for this server, or for a request, is never built here; the
    // build stops at the deadline or when the client leaves.
    const SetupStop stop(std::chrono::steady_clock::now() + services.config.timeouts.build, gone);
    const JobSize size = estimate_job_size(job);
    const JobEstimate estimated = estimate_job(job, size);
    if (auto over = over_limits(estimated, limits); !over.empty()) {
      return too_large(std::move(over), estimated, size, limits);
    }
    // Beyond the build budget the worker that runs the job builds it.
    if (!within_build_budget(size, limits)) {
      return new_job(job, estimated, size.end_s);
    }
    // One thread: preparation measures the stable step, and the handler
    // threads must not compete with the running jobs for every core.
    const std::shared_ptr<const PreparedJob> prepared =
        size.built ? size.built : std::make_shared<const PreparedJob>(prepare_job(job, 1));
    const JobEstimate estimate = estimate_job(*prepared);
    if (auto over = over_limits(estimate, limits); !over.empty()) {
      return too_large(std::move(over), estimate, size, limits);
    }
    return new_job(prepared->job, estimate, prepared->end_s);
  } catch (const InvalidJob& e) {
    return Refusal{http::status::bad_request, problem::kInvalidJob, "Invalid job", e.issues};
  } catch (const SetupStopped& e) {
    return Refusal{
        http::status::unprocessable_entity,
        problem::kJobTooLarge,
        "Job too large to prepare",
        {{"/discretization", std::string(e.what()) + " (this server allows " +
                                 std::to_string(services.config.timeouts.build.count() / 1000.0) +
                                 " s): use a coarser spacing"}}};
  }
}

namespace {

// 503 (the whole queue) or 429 (this client's share) with Retry-After and a sentence.
StringResponse queue_full_answer(const Services& s, const Request& req, bool whole_queue,
                                 std::int64_t queued, std::int64_t adding) {
  const Limits& l = s.config.limits;
  // A queue drains at the speed of its jobs: a try a minute later is soon enough.
  constexpr int kRetryAfter_s = 60;
  auto jobs = [](std::int64_t n) { return std::to_string(n) + (n == 1 ? " job" : " jobs"); };
  problem::Problem p;
  p.type = problem::kQueueFull;
  p.title = "The queue is full";
  p.instance = req.path;
  if (whole_queue) {
    p.status = http::status::service_unavailable;
    p.detail = jobs(queued) + " wait to run and this server queues at most " + jobs(l.max_queued) +
               " (--max-queued); this request would add " + jobs(adding) +
               ": try again once some have started";
  } else {
    p.status = http::status::too_many_requests;
    p.detail = jobs(queued) + " from " + quota_client(s, req) +
               " wait to run and one client may queue at most " + jobs(l.max_queued_per_client) +
               " (--max-queued-per-client); this request would add " + jobs(adding) +
               ": try again once some have started, or dismiss some";
  }
  StringResponse res = problem::make(p);
  res.set(http::field::retry_after, std::to_string(kRetryAfter_s));
  return res;
}

}  // namespace

std::string quota_client(const Services& s, const Request& req) {
  std::string who = credential_identity(req.msg.base(), s.config.token, s.sessions);
  return who.empty() ? req.client : who;
}

QueueQuota queue_quota(const Services& s, const Request& req) {
  QueueQuota q;
  q.max_queued = s.config.limits.max_queued;
  q.max_queued_per_client = s.config.limits.max_queued_per_client;
  q.client = quota_client(s, req);
  return q;
}

std::optional<StringResponse> queue_refusal(Services& s, const Request& req, std::int64_t adding) {
  const Limits& l = s.config.limits;
  if (l.max_queued > 0) {
    const auto counts = s.store.count_by_status();
    const auto it = counts.find("accepted");
    const std::int64_t queued = it == counts.end() ? 0 : it->second;
    if (queued + adding > l.max_queued) return queue_full_answer(s, req, true, queued, adding);
  }
  const std::string client = quota_client(s, req);
  if (l.max_queued_per_client > 0 && !client.empty()) {
    const std::int64_t mine = s.store.queued_from(client);
    if (mine + adding > l.max_queued_per_client) {
      return queue_full_answer(s, req, false, mine, adding);
    }
  }
  return std::nullopt;
}

std::optional<StringResponse> queue_refusal(const Services& s, const Request& req,
                                            const SubmitResult& r, std::int64_t adding) {
  if (r.kind == SubmitResult::Kind::queue_full) {
    return queue_full_answer(s, req, true, r.queued, adding);
  }
  if (r.kind == SubmitResult::Kind::client_queue_full) {
    return queue_full_answer(s, req, false, r.queued, adding);
  }
  return std::nullopt;
}

StringResponse refusal_response(const Refusal& r, const Request& req, const std::string& prefix,
                                const std::string& context) {
  problem::Problem p;
  p.status = r.status;
  p.type = r.type;
  p.title = r.title;
  p.instance = req.path;
  p.extra = r.extra;
  std::vector<JobIssue> located = r.issues;
  for (JobIssue& i : located) i.message = context + i.message;
  p.detail = located.size() == 1 ? located[0].message
                                 : std::to_string(located.size()) + " problems; see errors";
  p.extra["errors"] = problem::errors(located, prefix);
  return problem::make(p);
}

StringResponse created(bool is_new, const std::string& location, const nlohmann::json& body) {
  StringResponse res = json_response(is_new ? http::status::created : http::status::ok, body);
  res.set(http::field::location, location);
  return res;
}

StringResponse idempotency_conflict(const Request& req, const std::string& location) {
  problem::Problem p;
  p.status = http::status::conflict;
  p.type = problem::kIdempotencyConflict;
  p.title = "Idempotency-Key already used";
  p.detail = "this Idempotency-Key was used for another request (" + location +
             "); use a new key for a new request";
  p.instance = req.path;
  return problem::make(p);
}

}  // namespace gearsph::server
