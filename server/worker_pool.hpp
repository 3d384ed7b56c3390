#pragma once
// N workers, each running one job at a time with M OpenMP threads (N x M
// should not exceed the cores). A worker claims the oldest queued job from
// the store, runs it into data/jobs/{id}/ and records the outcome. Progress
// goes to memory at once (status requests read it there), to the event hub
// throttled, and to the store in batches by a flusher thread: nothing the
// HTTP side does ever waits for a simulation or its disk writes.
//
// With a lease (a shared store, many worker processes) the flusher is also
// the heartbeat: it renews the claims of the jobs running here, stops a run
// whose claim was lost (dismissed elsewhere, or reclaimed because the
// heartbeat could not reach the store for a whole lease), and the idle
// workers put jobs whose lease ran out back in the queue.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "server/dispatcher.hpp"
#include "server/event_hub.hpp"
#include "server/job_store.hpp"
#include "solver/run/runner.hpp"

namespace gearsph::server {

struct WorkerPoolOptions {
  int workers = 1;
  int threads_per_job = 1;  // the most a job takes
  // > 0: the workers share this many cores (ServerConfig::core_budget): a
  // worker claims a job only when a core is free, and the job takes the
  // threads it is worth (up to the free cores) when no other job waits,
  // one thread when others do.
  int core_budget = 0;
  std::filesystem::path jobs_dir;  // each job runs in jobs_dir / id
  std::chrono::milliseconds progress_interval{250};
  std::chrono::milliseconds flush_interval{1000};
  std::chrono::milliseconds poll_interval{2000};  // look for jobs queued by other processes
  Holder holder;                           // who claims; lease_s > 0: claims expire unless renewed
  int max_attempts = 3;                    // a job whose lease ran out this often fails
  std::string log_name = "gearsph serve";  // prefix of the log lines on stderr
};

class WorkerPool : public Dispatcher {
 public:
  WorkerPool(JobStore& store, EventHub& hub, WorkerPoolOptions options);
  ~WorkerPool();
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  void start() override;
  // A job was queued: wake an idle worker.
  void notify() override;
  // Claims no more jobs; running ones go on until they end or stop() (a
  // warm shutdown: running() tells when they are done).
  void drain() override;
  // Graceful stop: running jobs are cancelled at their next check and put
  // back in the queue (their message says so); returns once every worker
  // has finished and the last progress is stored.
  void stop() override;

  // The newest progress of a job running here.
  std::optional<ProgressUpdate> live(const std::string& id) const override;
  // Stops a job running here at its next check (it was dismissed); false if not running here.
  bool cancel(const std::string& id) override;
  int running() const override;
  const WorkerPoolOptions& options() const { return options_; }

  // A job running here: what its run reported so far (worker_pool.cpp).
  struct RunningJob;

 private:
  class Observer;

  void work();
  // Runs a claimed job on the cores `held` (core_budget mode: the first
  // core, taken before the claim; the job may take more, and hands back
  // what it is not worth).
  void run(const JobRecord& job, int& held);
  // What one run of a claimed job came to (worker_pool.cpp).
  struct Attempt;
  // The run itself, into its claim's directory `dir`: the simulation and,
  // when the job asks for it, the FE check.
  Attempt attempt(const JobRecord& job, RunningJob& rj, const std::filesystem::path& dir,
                  int& held);
  // Records the attempt's outcome under its claim, trying again while the
  // store is away; then publishes `dir` as the job's files, or discards it.
  void record(const JobRecord& job, const RunningJob& rj, const std::filesystem::path& dir,
              const Attempt& a);
  // The most threads the next job may take; in core_budget mode takes the
  // free cores into `held` when no other job waits.
  int offer_threads(int& held);
  // Hands `held` cores back to the budget and sets it to 0.
  void release_cores(int& held);
  void flush();
  void heartbeat();
  void reclaim();
  void flusher();
  void publish_status(const std::string& id);

  JobStore& store_;
  EventHub& hub_;
  WorkerPoolOptions options_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::uint64_t generation_ = 0;  // bumped by notify()
  std::map<std::string, std::shared_ptr<RunningJob>> running_;
  int cores_in_use_ = 0;  // core_budget mode: cores held by running jobs (mutex_)
  std::condition_variable core_freed_;
  std::atomic<bool> stopping_{false};
  std::atomic<bool> draining_{false};
  std::vector<std::thread> threads_;
  std::thread flusher_;
  std::mutex flush_mutex_;
  std::condition_variable flush_wake_;
  bool flusher_stop_ = false;
  std::chrono::steady_clock::time_point last_reclaim_{};
  std::mutex reclaim_mutex_;
};

}  // namespace gearsph::server
