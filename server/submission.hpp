#pragma once
// The steps every submission shares (POST /jobs, /processes/.../execution,
// /studies): a JSON body, an optional Idempotency-Key, and admission of a
// job: schema check, scene built to count particles and steps, limits.
#include <functional>
#include <optional>
#include <string>
#include <variant>

#include <nlohmann/json.hpp>

#include "server/http_types.hpp"
#include "server/job_store.hpp"
#include "server/services.hpp"

namespace gearsph::server {

// The body as JSON; 415 unless it is declared JSON, 400 if it does not
// parse or nests deeper than any job needs.
std::variant<nlohmann::json, StringResponse> read_json_body(const Request& req);

// The Idempotency-Key header (1-255 visible ASCII characters) with the
// request's canonical form; nullopt without the header, a 400 when malformed.
std::variant<std::optional<Idempotency>, StringResponse> idempotency_of(const Request& req,
                                                                        const std::string& scope,
                                                                        const nlohmann::json& body);

// Why a job is not taken: 400 invalid, 422 too large, 501 a check this
// service cannot run (fe_check without gmsh or CalculiX).
struct Refusal {
  http::status status = http::status::bad_request;
  std::string type, title;
  std::vector<JobIssue> issues;                     // pointers into the job
  nlohmann::json extra = nlohmann::json::object();  // estimate and limits
};

// 501 for a job asking for the FE check where gmsh or CalculiX is missing
// (`job` validated); nullopt when it can run.
std::optional<Refusal> fe_refusal(const Services& services, const nlohmann::json& job);

// Validates `job`, sizes it (gearsph::estimate_job_size) and checks the
// size limits; builds the scene (off the I/O threads) only within the build
// budget (Limits::max_built_particles), until the build timeout or `gone()`.
std::variant<NewJob, Refusal> admit_job(const Services& services, const nlohmann::json& job,
                                        const std::function<bool()>& gone = {});

// The queue quota (Limits::max_queued, max_queued_per_client): a 503 when
// `adding` more jobs would overfill the queue as a whole, a 429 when they
// would overfill this client's share of it, each with Retry-After and a
// sentence; nullopt when they fit.
std::optional<StringResponse> queue_refusal(Services& services, const Request& req,
                                            std::int64_t adding);
// The same for a submission the store refused (SubmitResult::Kind::queue_full,
// client_queue_full): the check above is a cheap early answer, the store's
// the one that holds under concurrent submissions.
std::optional<StringResponse> queue_refusal(const Services& services, const Request& req,
                                            const SubmitResult& r, std::int64_t adding);
// Whose share of the queue a request's jobs count against (NewJob::client).
std::string quota_client(const Services& services, const Request& req);
// The quota the store checks as it stores this request's jobs.
QueueQuota queue_quota(const Services& services, const Request& req);

// The problem answer for a refusal. `prefix` locates the job in the request
// body for the error pointers (e.g. "/inputs/job"); `context` starts each
// error detail (e.g. "job 3: ").
StringResponse refusal_response(const Refusal& r, const Request& req,
                                const std::string& prefix = "", const std::string& context = "");

// 201 Created (200 for a repeated idempotent request) with a Location.
StringResponse created(bool is_new, const std::string& location, const nlohmann::json& body);
// 409: the Idempotency-Key was used before with another request.
StringResponse idempotency_conflict(const Request& req, const std::string& location);

}  // namespace gearsph::server
