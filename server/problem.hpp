#pragma once
// Error answers as application/problem+json (RFC 9457): type, title,
// status, detail, instance, plus `errors: [{pointer, detail}]` for invalid
// jobs. Plain HTTP errors use "about:blank" with the status phrase as title;
// OGC API - Processes defines the job and process types.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "server/http_types.hpp"
#include "solver/job/job.hpp"

namespace gearsph::server::problem {

inline constexpr const char* kNoSuchJob =
    "http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0/no-such-job";
inline constexpr const char* kNoSuchProcess =
    "http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0/no-such-process";
inline constexpr const char* kResultNotReady =
    "http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0/result-not-ready";
inline constexpr const char* kInvalidJob = "urn:gearsph:problem:invalid-job";
inline constexpr const char* kMalformedJson = "urn:gearsph:problem:malformed-json";
inline constexpr const char* kNumberOutOfRange = "urn:gearsph:problem:number-out-of-range";
inline constexpr const char* kJobTooLarge = "urn:gearsph:problem:job-too-large";
inline constexpr const char* kIdempotencyConflict = "urn:gearsph:problem:idempotency-key-reused";
inline constexpr const char* kJobFailed = "urn:gearsph:problem:job-failed";
inline constexpr const char* kStoreUnavailable = "urn:gearsph:problem:store-unavailable";
inline constexpr const char* kQueueFull = "urn:gearsph:problem:queue-full";
inline constexpr const char* kRenderingUnavailable = "urn:gearsph:problem:rendering-unavailable";
inline constexpr const char* kFeUnavailable = "urn:gearsph:problem:fe-unavailable";
inline constexpr const char* kInvalidParameter = "urn:gearsph:problem:invalid-parameter";

struct Problem {
  http::status status = http::status::internal_server_error;
  std::string type = "about:blank";
  std::string title;  // defaults to the status phrase
  std::string detail;
  std::string instance;                             // the request path
  nlohmann::json extra = nlohmann::json::object();  // more members (errors, estimate, ...)
};

StringResponse make(const Problem& p);
// about:blank with the status phrase as title.
StringResponse plain(http::status status, const std::string& detail, const std::string& instance);
// 404, OGC's no-such-job: there is no job with the request's `id` (or the
// request names none).
StringResponse no_such_job(const Request& req);
// 404, OGC's no-such-process: the service has one process, kProcessId.
StringResponse no_such_process(const Request& req);
// 400, invalid-parameter: a query parameter outside its range, `detail`
// saying what is allowed.
StringResponse invalid_parameter(const Request& req, const std::string& detail);
// `errors: [{pointer, detail}]` from the issues of an invalid job; pointers
// are prefixed with `prefix` (e.g. "/inputs/job" for an OGC execute request).
nlohmann::json errors(const std::vector<JobIssue>& issues, const std::string& prefix = "");

}  // namespace gearsph::server::problem
