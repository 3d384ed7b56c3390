#include "server/store_watcher.hpp"
#include "server/log.hpp"

#include "server/attempt_dirs.hpp"
#include "server/metrics.hpp"

#include <cstdio>
#include <optional>
#include <set>

#include "server/documents.hpp"

namespace gearsph::server {

StoreWatcher::StoreWatcher(JobStore& store, EventHub& hub, const Dispatcher& local,
                           StoreWatcherOptions options)
    : store_(store), hub_(hub), local_(local), options_(options) {}

StoreWatcher::~StoreWatcher() {
  stop();
}

void StoreWatcher::start() {
  // Learn what is there before the server answers anyone: a first poll
  // made later took changes of jobs submitted meanwhile for history, and a
  // client already following such a job never heard its final status (its
  // stream stayed open with keep-alives).
  try {
    poll(std::chrono::duration<double>(options_.interval).count() + 5.0);
  } catch (const std::exception& e) {
    log_line(LogLevel::warning, "gearsph serve: watching the job store failed: %s\n", e.what());
  }
  thread_ = std::thread([this] { loop(); });
}

void StoreWatcher::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void StoreWatcher::loop() {
  using Clock = std::chrono::steady_clock;
  auto last_ok = Clock::now();
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait_for(lock, options_.interval, [this] { return stop_; });
      if (stop_) return;
    }
    // Everything changed since the last poll that succeeded, with a margin
    // for transactions that committed late and for clock steps.
    const auto now = Clock::now();
    const double window = std::chrono::duration<double>(now - last_ok).count() + 5.0;
    try {
      if (options_.reclaim) {
        const Recovery r = store_.reclaim_expired(options_.max_attempts);
        counters().lease_expiries += static_cast<std::int64_t>(r.requeued.size());
        counters().lease_failures += static_cast<std::int64_t>(r.failed.size());
        for (const std::string& id : r.requeued) {
          log_line(LogLevel::warning,
                   "gearsph serve: job %s: its worker stopped renewing its lease; it is "
                   "queued again\n",
                   id.c_str());
        }
        for (const std::string& id : r.failed) {
          discard_attempts(options_.jobs_dir, id);
          log_line(LogLevel::warning,
                   "gearsph serve: job %s: its worker stopped renewing its lease; "
                   "it failed\n",
                   id.c_str());
        }
      }
      poll(window);
      last_ok = now;
    } catch (const std::exception& e) {
      log_line(LogLevel::warning, "gearsph serve: watching the job store failed: %s\n", e.what());
    }
  }
}

void StoreWatcher::poll(double window_s) {
  std::set<std::string> present;
  for (const JobRecord& job : store_.active_or_changed_within(window_s)) {
    present.insert(job.id);
    Seen now{job.status, job.message, job.step};
    const auto it = seen_.find(job.id);
    const std::optional<Seen> before =
        it == seen_.end() ? std::nullopt : std::optional<Seen>(it->second);
    seen_[job.id] = now;
    // The first poll only learns what is there: its events are history.
    if (!primed_ || local_.live(job.id)) continue;
    if (!before || before->status != now.status || before->message != now.message) {
      hub_.publish(job.id, "status", status_document(job).dump(), is_terminal_status(job.status));
    } else if (job.status == JobStatus::running && before->step != now.step) {
      nlohmann::json p = status_document(job);
      nlohmann::json d = {
          {"jobID", job.id},    {"status", "running"},  {"progress", p["progress"]},
          {"step", job.step},   {"steps", job.steps},   {"simulated_s", job.simulated_s},
          {"end_s", job.end_s}, {"wall_s", job.wall_s}, {"eta_s", job.eta_s}};
      hub_.publish(job.id, "progress", d.dump());
    }
  }
  primed_ = true;
  // Forget finished jobs once they left the window.
  for (auto it = seen_.begin(); it != seen_.end();) {
    if (!present.count(it->first) && is_terminal_status(it->second.status)) {
      it = seen_.erase(it);
    } else {
      ++it;
    }
  }
}

}  // namespace gearsph::server
