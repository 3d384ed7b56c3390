// The service describing itself: landing page, conformance, health, the job
// schema and the one process (OGC API - Processes).
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "server/openapi.hpp"
#include "server/problem.hpp"
#include "server/routes.hpp"
#include "server/static_files.hpp"
#include "solver/job/job.hpp"

namespace gearsph::server::routes {

namespace {

constexpr const char* kOpenApiType = "application/vnd.oai.openapi+json;version=3.0";

nlohmann::json process_summary() {
  return {{"id", kProcessId},
          {"title", "GearSPH simulation"},
          {"description",
           "Runs one SPH simulation of elastic solids (2D plane strain) described by a job "
           "document (see /schema) and stores summary.json, history.csv, results.h5 and "
           "results.xmf."},
          {"version", version()},
          {"jobControlOptions", {"async-execute", "dismiss"}},
          {"outputTransmission", {"value", "reference"}},
          {"links",
           {link(std::string("/processes/") + kProcessId, "self", "application/json",
                 "process description"),
            link(std::string("/processes/") + kProcessId + "/execution",
                 "http://www.opengis.net/def/rel/ogc/1.0/execute", "application/json",
                 "execute (POST a job)")}}};
}

}  // namespace

Response landing(Services& s, Request& req) {
  if (wants_html(req)) {
    if (auto page = serve_static(req, s.config.web_root)) return std::move(*page);
  }
  return json_response(
      http::status::ok,
      {{"title", "GearSPH job service"},
       {"description",
        "SPH simulation of rack-and-pinion gear meshing as a job service (OGC API - Processes)."},
       {"version", version()},
       {"links",
        {link("/", "self", "application/json", "this document"),
         link("/api", "service-desc", kOpenApiType, "the API definition (OpenAPI 3.0)"),
         link("/conformance", "http://www.opengis.net/def/rel/ogc/1.0/conformance",
              "application/json", "conformance classes"),
         link("/processes", "http://www.opengis.net/def/rel/ogc/1.0/processes", "application/json",
              "processes"),
         link("/jobs", "http://www.opengis.net/def/rel/ogc/1.0/job-list", "application/json",
              "jobs"),
         link("/schema", "describedby", "application/schema+json", "the job schema"),
         link("/health", "status", "application/json", "health and queue"),
         link("/events", "alternate", "text/event-stream", "events of all jobs")}}});
}

Response api_definition(Services&, Request&) {
  // The document as written, with this build's version.
  static const std::string text = [] {
    nlohmann::json doc = nlohmann::json::parse(openapi_document());
    doc["info"]["version"] = version();
    return doc.dump(1) + "\n";
  }();
  StringResponse res = text_response(http::status::ok, text, kOpenApiType);
  res.set(http::field::cache_control, "no-cache");
  return res;
}

Response conformance(Services&, Request&) {
  return json_response(http::status::ok,
                       {{"conformsTo",
                         {"http://www.opengis.net/spec/ogcapi-processes-1/1.0/conf/core",
                          "http://www.opengis.net/spec/ogcapi-processes-1/1.0/conf/json",
                          "http://www.opengis.net/spec/ogcapi-processes-1/1.0/conf/job-list",
                          "http://www.opengis.net/spec/ogcapi-processes-1/1.0/conf/oas30",
                          "http://www.opengis.net/spec/ogcapi-processes-1/1.0/conf/dismiss"}}});
}

Response health(Services& s, Request&) {
  const double uptime =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - s.started).count();
  // What the service needs: the job store (checked every second by the
  // queue counts, and by every request) and the results directory.
  const auto [store_error, store_down_s] = s.store_down();
  nlohmann::json store = {{"status", store_error.empty() ? "up" : "down"}};
  if (!store_error.empty()) {
    store["detail"] = store_error;
    store["down_for_s"] = store_down_s;
  }
  const bool results_ok = ::access(s.jobs_dir.c_str(), W_OK | X_OK) == 0;
  nlohmann::json results = {{"status", results_ok ? "up" : "down"}, {"path", s.jobs_dir.string()}};
  if (!results_ok) results["detail"] = std::string("not writable: ") + std::strerror(errno);
  const bool up = store_error.empty() && results_ok;
  StringResponse res = json_response(up ? http::status::ok : http::status::service_unavailable,
                                     {{"status", up ? "ok" : "degraded"},
                                      {"dependencies", {{"store", store}, {"results", results}}},
                                      {"version", version()},
                                      {"uptime_s", uptime},
                                      {"queue", s.queue_counts()},
                                      {"workers", s.config.workers},
                                      {"threads_per_job", s.config.threads_per_job},
                                      {"core_budget", s.config.core_budget},
                                      {"running_here", s.workers.running()},
                                      {"connections", s.connections.load()},
                                      {"event_streams", s.hub.subscribers()},
                                      {"image_cache", s.images.stats()},
                                      {"requests", s.requests.load()}});
  if (!up) res.set(http::field::retry_after, "5");
  return res;
}

Response schema(Services&, Request&) {
  StringResponse res =
      text_response(http::status::ok, job_schema().dump(2) + "\n", "application/schema+json");
  res.set(http::field::cache_control, "no-cache");
  return res;
}

Response processes(Services&, Request&) {
  return json_response(http::status::ok,
                       {{"processes", {process_summary()}},
                        {"links", {link("/processes", "self", "application/json")}}});
}

Response process(Services&, Request& req) {
  if (req.param("process") != kProcessId) return problem::no_such_process(req);
  nlohmann::json d = process_summary();
  d["inputs"] = {
      {"job",
       {{"title", "Job"},
        {"description",
         "The job document; POST it as the body of /processes/gearsph-simulation/execution "
         "(bare, or as {\"inputs\": {\"job\": ...}}) or of /jobs."},
        {"minOccurs", 1},
        {"maxOccurs", 1},
        {"schema", job_schema()}}}};
  // In GET /jobs/{id}/results under these ids: summary as a value, the
  // others as links.
  d["outputs"] = {
      {"summary",
       {{"title", "Summary numbers"},
        {"description", "summary.json: peak stresses and where, forces, stability, energy drift"},
        {"schema", {{"type", "object"}, {"contentMediaType", "application/json"}}}}},
      {"history",
       {{"title", "Time histories"},
        {"description", "history.csv, by reference"},
        {"schema", {{"type", "string"}, {"contentMediaType", "text/csv"}}}}},
      {"results",
       {{"title", "Particle snapshots (HDF5, with an XDMF sidecar for ParaView)"},
        {"description", "results.h5, by reference; results.xmf is among the job's files"},
        {"schema", {{"type", "string"}, {"contentMediaType", "application/x-hdf5"}}}}}};
  return json_response(http::status::ok, d);
}

}  // namespace gearsph::server::routes
