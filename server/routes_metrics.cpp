// GET /metrics: the service for Prometheus (text exposition format 0.0.4):
// the queue by status, the workers seen and their last heartbeat, the jobs'
// wall times as a histogram, and this process's counters (server/metrics.hpp).
// It answers while the store is away (gearsph_store_up 0), which is when an
// operator needs it most.
#include <sstream>

#include "server/metrics.hpp"
#include "server/routes.hpp"

namespace gearsph::server {

Counters& counters() {
  static Counters c;
  return c;
}

namespace routes {

namespace {

// A label value, escaped as the format requires.
std::string label(const std::string& v) {
  std::string out;
  for (char c : v) {
    if (c == '\\' || c == '"') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out;
}

void family(std::ostringstream& o, const char* name, const char* type, const char* help) {
  o << "# HELP " << name << ' ' << help << "\n# TYPE " << name << ' ' << type << '\n';
}

}  // namespace

Response metrics(Services& s, Request&) {
  std::ostringstream o;
  o.precision(10);
  family(o, "gearsph_jobs", "gauge", "Jobs in the store by status.");
  for (const auto& [status, n] : s.queue_counts()) {
    o << "gearsph_jobs{status=\"" << status << "\"} " << n << '\n';
  }
  family(o, "gearsph_jobs_running_here", "gauge", "Jobs running in this process.");
  o << "gearsph_jobs_running_here " << s.workers.running() << '\n';

  bool store_up = true;
  std::vector<WorkerSeen> workers;
  Durations d;
  const std::vector<double> bounds = {1, 10, 60, 600, 3600, 36000};
  try {
    workers = s.store.workers_seen(600);
    d = s.store.durations(bounds);
  } catch (const std::exception& e) {
    store_up = false;
    s.note_store_down(e.what());
  }
  if (!s.store_down().first.empty()) store_up = false;
  family(o, "gearsph_store_up", "gauge", "1 if the job store answers, 0 if not.");
  o << "gearsph_store_up " << (store_up ? 1 : 0) << '\n';
  family(o, "gearsph_workers_seen", "gauge",
         "Worker processes whose heartbeat the store saw in the last 10 minutes.");
  o << "gearsph_workers_seen " << workers.size() << '\n';
  family(o, "gearsph_worker_heartbeat_age_seconds", "gauge",
         "Seconds since each worker's last heartbeat (store clock).");
  for (const WorkerSeen& w : workers) {
    o << "gearsph_worker_heartbeat_age_seconds{worker=\"" << label(w.name) << "\"} " << w.seen_ago_s
      << '\n';
  }
  family(o, "gearsph_worker_running_jobs", "gauge", "Jobs each worker ran at its last heartbeat.");
  for (const WorkerSeen& w : workers) {
    o << "gearsph_worker_running_jobs{worker=\"" << label(w.name) << "\"} " << w.running << '\n';
  }
  if (store_up) {
    family(o, "gearsph_job_wall_seconds", "histogram",
           "Wall time of the jobs that ended (successful or failed).");
    for (std::size_t i = 0; i < d.bounds.size(); ++i) {
      o << "gearsph_job_wall_seconds_bucket{le=\"" << d.bounds[i] << "\"} " << d.at_most[i] << '\n';
    }
    o << "gearsph_job_wall_seconds_bucket{le=\"+Inf\"} " << d.count << '\n';
    o << "gearsph_job_wall_seconds_sum " << d.sum_s << '\n';
    o << "gearsph_job_wall_seconds_count " << d.count << '\n';
  }
  const Counters& c = counters();
  const struct {
    const char* name;
    const char* help;
    std::int64_t value;
  } totals[] = {
      {"gearsph_lease_expiries_total",
       "Running jobs this process queued again because their lease ran out.",
       c.lease_expiries.load()},
      {"gearsph_lease_failures_total",
       "Running jobs this process failed because their lease ran out max-attempts times.",
       c.lease_failures.load()},
      {"gearsph_requeues_total", "Runs here stopped by a shutdown and queued again.",
       c.requeues.load()},
      {"gearsph_claims_lost_total",
       "Runs here whose claim another worker took (their files discarded).", c.claims_lost.load()},
      {"gearsph_store_retries_total",
       "Store operations retried after a transient error (not lost leases).",
       c.store_retries.load()},
      {"gearsph_store_unavailable_responses_total",
       "Requests answered 503 because the store was away.", c.store_unavailable.load()},
      {"gearsph_jobs_pruned_total", "Ended jobs deleted by the retention setting.",
       c.jobs_pruned.load()},
      {"gearsph_http_requests_total", "HTTP requests answered.", s.requests.load()},
  };
  for (const auto& t : totals) {
    family(o, t.name, "counter", t.help);
    o << t.name << ' ' << t.value << '\n';
  }
  StringResponse res = text_response(http::status::ok, o.str(), "text/plain; version=0.0.4");
  res.set(http::field::cache_control, "no-store");
  return res;
}

}  // namespace routes
}  // namespace gearsph::server
