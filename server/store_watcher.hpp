#pragma once
// Events of jobs that other processes run. When the jobs run elsewhere
// (worker processes on a shared store, a Slurm cluster), this server learns
// of their progress only from the store: a thread polls it and publishes a
// status event for every change of status or message and a progress event
// for every new step, so event streams and the dashboard work the same as
// with the server's own workers. Jobs running in this process are skipped
// (their pool publishes them). The same thread also puts jobs whose lease
// ran out back in the queue, so that happens even with no idle worker.
#include <chrono>
#include <condition_variable>
#include <map>
#include <mutex>
#include <string>
#include <thread>

#include "server/dispatcher.hpp"
#include "server/event_hub.hpp"
#include "server/job_store.hpp"

namespace gearsph::server {

struct StoreWatcherOptions {
  std::chrono::milliseconds interval{500};
  bool reclaim = false;  // also reclaim expired leases
  int max_attempts = 3;
  std::filesystem::path jobs_dir;  // where a failed job's attempt directories are deleted
};

class StoreWatcher {
 public:
  StoreWatcher(JobStore& store, EventHub& hub, const Dispatcher& local,
               StoreWatcherOptions options);
  ~StoreWatcher();
  StoreWatcher(const StoreWatcher&) = delete;
  StoreWatcher& operator=(const StoreWatcher&) = delete;

  void start();
  void stop();

 private:
  struct Seen {
    JobStatus status = JobStatus::accepted;
    std::string message;
    std::int64_t step = 0;
  };
  void loop();
  void poll(double window_s);
  // Until the next look: the interval, or (PostgreSQL) a change announced
  // sooner. False if nothing was announced.
  bool wait_for_news();

  JobStore& store_;
  EventHub& hub_;
  const Dispatcher& local_;
  StoreWatcherOptions options_;
  std::map<std::string, Seen> seen_;
  bool primed_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace gearsph::server
