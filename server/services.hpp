#pragma once
// What request handlers work with: the configuration, the job store, the
// workers (for live progress and cancellation) and the event hub. Owned by
// the Server; handlers receive it by reference.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>

#include <nlohmann/json.hpp>

#include "server/attempt_dirs.hpp"
#include "server/config.hpp"
#include "server/dispatcher.hpp"
#include "server/documents.hpp"
#include "server/event_hub.hpp"
#include "server/image_cache.hpp"
#include "server/job_store.hpp"
#include "server/preview_cache.hpp"
#include "server/sessions.hpp"
#include "server/speed_calibration.hpp"

namespace gearsph::server {

struct Services {
  Services(const ServerConfig& c, JobStore& s, Dispatcher& w, EventHub& h)
      : config(c),
        store(s),
        workers(w),
        hub(h),
        jobs_dir(results_dir_of(c)),
        images(c.image_cache_bytes) {}

  const ServerConfig& config;
  JobStore& store;
  Dispatcher& workers;  // the worker pool, or the Slurm dispatcher
  EventHub& hub;
  std::filesystem::path jobs_dir;
  ImageCache images;  // rendered images, outside the job directories
  // Previews by job: 16 MB holds a few dozen with their particles listed.
  PreviewCache previews{16u << 20};
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  std::atomic<int> connections{0};
  // Open event streams: at most half the connections (max_event_streams),
  // so that idle streams never lock out the requests.
  std::atomic<int> event_streams{0};
  int max_event_streams() const { return std::max(1, config.limits.max_connections / 2); }
  std::atomic<std::int64_t> requests{0};
  std::atomic<bool> stopping{false};    // shutting down: no more keep-alive
  std::atomic<unsigned short> port{0};  // the port listened on (known once bound)
  // The dashboard's sessions and the failed logins by address (sessions.hpp).
  Sessions sessions{store, config.token, kSessionLifetime, kMaxSessions};
  LoginThrottle login_throttle{kLoginFailuresPerMinute, std::chrono::seconds(60)};

  // This machine's speed, measured once, by the first caller (a preview
  // before any job has finished); the callers at the same time wait for it.
  const SpeedCalibration& calibration() {
    std::call_once(calibration_once_, [this] {
      calibration_ =
          calibrate_speed(std::max(1, config.threads_per_job), [this] { return stopping.load(); });
    });
    return calibration_;
  }

  // The directory whose files are the job's (attempt_dirs.hpp).
  std::filesystem::path job_dir(const JobRecord& job) const { return results_dir(jobs_dir, job); }

  // Jobs by status as /health shows them: refreshed every second off the
  // I/O threads, so a health check never waits for the store.
  void refresh_queue_counts() {
    std::map<std::string, std::int64_t> counts;
    try {
      counts = store.count_by_status();
    } catch (const std::exception& e) {
      note_store_down(e.what());
      return;  // the store is away: keep the last counts
    }
    std::lock_guard<std::mutex> lock(counts_mutex_);
    queue_counts_ = std::move(counts);
    store_error_.clear();
  }

  // The store failed a request or the counts' refresh; the next refresh
  // that succeeds clears it.
  void note_store_down(const std::string& why) {
    std::lock_guard<std::mutex> lock(counts_mutex_);
    if (store_error_.empty()) store_down_since_ = std::chrono::steady_clock::now();
    store_error_ = why;
  }
  // "" while the store answers; else the last failure and its age in seconds.
  std::pair<std::string, double> store_down() const {
    std::lock_guard<std::mutex> lock(counts_mutex_);
    if (store_error_.empty()) return {"", 0.0};
    return {store_error_,
            std::chrono::duration<double>(std::chrono::steady_clock::now() - store_down_since_)
                .count()};
  }
  std::map<std::string, std::int64_t> queue_counts() const {
    std::lock_guard<std::mutex> lock(counts_mutex_);
    return queue_counts_;
  }
  nlohmann::json status_of(const JobRecord& job) const {
    return status_document(job, workers.live(job.id));
  }
  // A status event for a change made by a handler (submitted, dismissed).
  void publish_status(const JobRecord& job) const {
    hub.publish(job.id, "status", status_of(job).dump(), is_terminal_status(job.status));
  }

 private:
  std::once_flag calibration_once_;
  SpeedCalibration calibration_;
  mutable std::mutex counts_mutex_;
  std::string store_error_;
  std::chrono::steady_clock::time_point store_down_since_;
  std::map<std::string, std::int64_t> queue_counts_;
};

}  // namespace gearsph::server
