#include "server/store_watcher.hpp"

#include <cstdio>
#include <optional>
#include <set>
#include <thread>

#include "server/attempt_dirs.hpp"
#include "server/documents.hpp"
#include "server/log.hpp"
#include "server/metrics.hpp"

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

bool StoreWatcher::wait_for_news() {
  const auto until = std::chrono::steady_clock::now() + options_.interval;
  if (!store_.notifies()) {
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait_until(lock, until, [this] { return stop_; });
    return true;  // no news without asking
  }
  // PostgreSQL: LISTEN/NOTIFY. A change is read at once; without one, the
  // table is not read at all (the leases are still looked at below).
  while (std::chrono::steady_clock::now() < until) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (stop_) return false;
    }
    try {
      if (store_.wait_for_change(std::chrono::milliseconds(100))) return true;
    } catch (const std::exception&) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      return true;  // the next poll says what is wrong
    }
  }
  return false;
}

void StoreWatcher::loop() {
  using Clock = std::chrono::steady_clock;
  auto last_poll = Clock::now();
  for (;;) {
    const bool news = wait_for_news();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (stop_) return;
    }
    // Everything changed since the last poll that succeeded, with a margin
    // for transactions that committed late and for clock steps. Without
    // news, every 5 s all the same (a notification lost with a connection).
    const auto now = Clock::now();
    const double since = std::chrono::duration<double>(now - last_poll).count();
    const double window = since + 5.0;
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
      if (news || since >= 5.0) {
        poll(window);
        last_poll = now;
      }
    } catch (const std::exception& e) {
      log_line(LogLevel::warning, "gearsph serve: watching the job store failed: %s\n", e.what());
    }
  }
}

void StoreWatcher::poll(double window_s) {
  std::set<std::string> present;
  // The first look learns every active job; later ones read what changed.
  const std::vector<JobRecord> jobs =
      primed_ ? store_.changed_within(window_s) : store_.active_or_changed_within(window_s);
  for (const JobRecord& job : jobs) {
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
