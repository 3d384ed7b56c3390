#pragma once
// Counters of what this process has done since it started, for /metrics
// (the Prometheus text format; routes_metrics.cpp). Each process counts
// its own: Prometheus adds them up across API nodes. What is shared (the
// queue, the workers' heartbeats, the jobs' durations) comes from the store.
#include <atomic>
#include <cstdint>

namespace gearsph::server {

struct Counters {
  std::atomic<std::int64_t> lease_expiries{
      0};  // running jobs this process put back (lease ran out)
  std::atomic<std::int64_t> lease_failures{0};  // ... and failed after max attempts
  std::atomic<std::int64_t> requeues{0};        // runs stopped by a shutdown and queued again
  std::atomic<std::int64_t> claims_lost{0};     // runs here whose claim another worker took
  std::atomic<std::int64_t> store_retries{0};   // store operations retried after a transient error
  std::atomic<std::int64_t> store_unavailable{0};  // requests answered 503 (the store away)
  std::atomic<std::int64_t> jobs_pruned{0};        // ended jobs deleted by the retention
};

Counters& counters();

}  // namespace gearsph::server
