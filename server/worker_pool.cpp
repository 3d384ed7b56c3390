#include "server/worker_pool.hpp"

#include <algorithm>
#include <cstdio>

#include "server/attempt_dirs.hpp"
#include "server/documents.hpp"
#include "server/fe_stage_estimate.hpp"
#include "server/log.hpp"
#include "server/metrics.hpp"
#include "solver/core/setup_progress.hpp"
#include "solver/job/job.hpp"
#include "solver/run/execute.hpp"

namespace gearsph::server {

namespace {

using Clock = std::chrono::steady_clock;

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

nlohmann::json progress_document(const ProgressUpdate& u, std::int64_t steps, double end_s) {
  nlohmann::json fe = nullptr;
  if (!u.fe_check_json.empty()) fe = nlohmann::json::parse(u.fe_check_json, nullptr, false);
  return {{"jobID", u.id},
          {"status", "running"},
          {"stage", u.stage},
          {"progress", u.progress},
          {"step", u.step},
          {"steps", steps},
          {"simulated_s", u.simulated_s},
          {"end_s", end_s},
          {"wall_s", u.wall_s},
          {"stage_wall_s", stage_wall(u.wall_s, fe)},
          {"eta_s", u.eta_s},
          {"fe_check", fe},
          {"setup", nullptr}};  // the set-up is over (its events below)
}

// A set-up past a second (SetupProgressScope): what it is doing.
nlohmann::json setup_document(const std::string& id, std::int64_t steps, const SetupStatus& s) {
  return {{"jobID", id},
          {"status", "running"},
          {"progress", 0},
          {"step", 0},
          {"steps", steps},
          {"setup", {{"stage", s.stage}, {"fraction", s.fraction}, {"elapsed_s", s.elapsed_s}}}};
}

}  // namespace

struct WorkerPool::RunningJob {
  std::string id;
  std::string claim;  // the claim's token: every store update of the run names it
  std::atomic<bool> dismissed{false};
  std::atomic<bool> lost{false};  // the store no longer has it running here
  std::mutex mutex;               // guards the fields below
  Progress progress;
  bool dirty = false;
  Clock::time_point last_event{};
  // The FE check after the time loop (fe_stage_estimate.hpp), when the job asks for it.
  bool fe = false;
  FeStageEstimate fe_estimate;
  std::string stage = "sph";
  StageProgress fe_progress;
  Clock::time_point fe_reported{};  // when fe_progress came
  double sph_wall_s = 0.0;          // the time loop's, once it is over
};

namespace {

ProgressUpdate live_update(const WorkerPool::RunningJob& j) {
  const Progress& p = j.progress;
  ProgressUpdate u{j.id,    p.step, p.time_s, p.wall_s, p.eta_s, percent(p.step, p.steps),
                   j.stage, ""};
  if (!j.fe) return u;
  if (j.stage != "fe_check") {
    count_fe_stage(u, j.fe_estimate, nullptr);
    return u;
  }
  const FeStageNow now{j.fe_progress.fraction, j.fe_progress.elapsed_s,
                       std::chrono::duration<double>(Clock::now() - j.fe_reported).count(),
                       j.sph_wall_s};
  count_fe_stage(u, j.fe_estimate, &now);
  return u;
}

}  // namespace

// Runs on the simulation thread: cheap, never blocks on I/O.
class WorkerPool::Observer : public RunObserver {
 public:
  Observer(WorkerPool& pool, RunningJob& job) : pool_(pool), job_(job) {}

  void on_progress(const Progress& p) override {
    const auto now = Clock::now();
    bool publish = false;
    {
      std::lock_guard<std::mutex> lock(job_.mutex);
      job_.progress = p;
      job_.dirty = true;
      if (now - job_.last_event >= pool_.options_.progress_interval || p.step >= p.steps) {
        job_.last_event = now;
        publish = true;
      }
    }
    if (publish) publish_progress();
  }

  void on_stage(const StageProgress& s) override {
    {
      std::lock_guard<std::mutex> lock(job_.mutex);
      if (job_.stage == "sph") job_.sph_wall_s = job_.progress.wall_s;
      job_.stage = s.stage;
      job_.fe_progress = s;
      job_.fe_reported = Clock::now();
      job_.dirty = true;
      job_.last_event = Clock::now();
    }
    publish_progress();
  }

  bool cancelled() override {
    return job_.dismissed.load() || job_.lost.load() || pool_.stopping_.load();
  }

 private:
  void publish_progress() {
    ProgressUpdate u;
    std::int64_t steps = 0;
    double end_s = 0;
    {
      std::lock_guard<std::mutex> lock(job_.mutex);
      u = live_update(job_);
      steps = job_.progress.steps;
      end_s = job_.progress.end_s;
    }
    pool_.hub_.publish(job_.id, "progress", progress_document(u, steps, end_s).dump());
  }

  WorkerPool& pool_;
  RunningJob& job_;
};

WorkerPool::WorkerPool(JobStore& store, EventHub& hub, WorkerPoolOptions options)
    : store_(store), hub_(hub), options_(std::move(options)) {}

WorkerPool::~WorkerPool() {
  stop();
}

void WorkerPool::start() {
  for (int i = 0; i < options_.workers; ++i) threads_.emplace_back([this] { work(); });
  flusher_ = std::thread([this] { flusher(); });
}

void WorkerPool::notify() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++generation_;
  }
  // Every idle worker: a study queues many jobs at once, and a worker left
  // asleep would start only at its next poll (2 s). Those that find nothing
  // go back to sleep.
  wake_.notify_all();
}

void WorkerPool::drain() {
  draining_ = true;
  wake_.notify_all();
}

void WorkerPool::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  core_freed_.notify_all();
  for (std::thread& t : threads_) {
    if (t.joinable()) t.join();
  }
  {
    std::lock_guard<std::mutex> lock(flush_mutex_);
    flusher_stop_ = true;
  }
  flush_wake_.notify_all();
  if (flusher_.joinable()) flusher_.join();
}

std::optional<ProgressUpdate> WorkerPool::live(const std::string& id) const {
  std::shared_ptr<RunningJob> job;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = running_.find(id);
    if (it == running_.end()) return std::nullopt;
    job = it->second;
  }
  std::lock_guard<std::mutex> lock(job->mutex);
  return live_update(*job);
}

bool WorkerPool::cancel(const std::string& id) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = running_.find(id);
  if (it == running_.end()) return false;
  it->second->dismissed = true;
  return true;
}

int WorkerPool::running() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(running_.size());
}

void WorkerPool::release_cores(int& held) {
  if (held <= 0) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    cores_in_use_ -= held;
  }
  held = 0;
  core_freed_.notify_all();
}

void WorkerPool::work() {
  // Claims that failed in a row (the store away): the pause before the next
  // try doubles up to 10 s, and the log says so at the 1st, 2nd, 4th, ...
  int failures = 0;
  while (!stopping_) {
    std::uint64_t seen = 0;
    int held = 0;  // cores of the budget this worker holds
    {
      std::unique_lock<std::mutex> lock(mutex_);
      if (options_.core_budget > 0) {
        // A job is claimed only with a core to run it on.
        core_freed_.wait(lock,
                         [&] { return stopping_.load() || cores_in_use_ < options_.core_budget; });
        if (stopping_) return;
        ++cores_in_use_;
        held = 1;
      }
      seen = generation_;
    }
    std::optional<JobRecord> job;
    auto pause = options_.poll_interval;
    try {
      if (options_.holder.lease_s > 0) reclaim();
      if (!draining_) job = store_.claim(options_.holder);
      if (failures > 0) {
        log_line(LogLevel::info, "%s: the job store answers again, after %d failed tries\n",
                 options_.log_name.c_str(), failures);
      }
      failures = 0;
    } catch (const std::exception& e) {
      ++failures;
      ++counters().store_retries;
      if ((failures & (failures - 1)) == 0) {
        log_line(LogLevel::warning, "%s: claiming a job failed (%d in a row): %s\n",
                 options_.log_name.c_str(), failures, e.what());
      }
      pause = std::min<std::chrono::milliseconds>(
          std::chrono::milliseconds(10'000), options_.poll_interval * (1 << std::min(failures, 6)));
    }
    if (job) {
      if (stopping_) {
        store_.requeue(job->id, "re-queued: the server was stopping when this job was claimed",
                       job->claim);
        release_cores(held);
        return;
      }
      try {
        run(*job, held);
      } catch (const std::exception& e) {
        // The store failed while recording the outcome; the job stays
        // running in the store and is re-queued at the next start (or when
        // its lease runs out).
        log_line(LogLevel::warning, "%s: job %s: recording its outcome failed: %s\n",
                 options_.log_name.c_str(), job->id.c_str(), e.what());
      }
      release_cores(held);
      continue;
    }
    release_cores(held);
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait_for(lock, pause, [&] { return stopping_.load() || generation_ != seen; });
  }
}

int WorkerPool::offer_threads(int& held) {
  if (options_.core_budget <= 0) return options_.threads_per_job;
  // Others waiting: one thread each serves the queue soonest (N jobs in
  // about N / cores job-times); alone, the job may take every free core.
  bool others_waiting = true;
  try {
    const std::map<std::string, std::int64_t> counts = store_.count_by_status();
    const auto queued = counts.find("accepted");
    others_waiting = queued != counts.end() && queued->second > 0;
  } catch (const std::exception&) {
    // The store will say more when the job's outcome is recorded.
  }
  std::lock_guard<std::mutex> lock(mutex_);
  const int extra = others_waiting ? 0 : std::max(0, options_.core_budget - cores_in_use_);
  cores_in_use_ += extra;
  held += extra;
  return std::max(1, std::min(options_.threads_per_job, held));
}

struct WorkerPool::Attempt {
  JobStatus outcome = JobStatus::failed;
  bool cancelled = false;
  std::string message;
  ProgressUpdate last;
  std::int64_t steps = 0;
};

WorkerPool::Attempt WorkerPool::attempt(const JobRecord& job, RunningJob& rj,
                                        const std::filesystem::path& dir, int& held) {
  Attempt a;
  a.last.id = job.id;
  a.steps = job.steps;
  try {
    // Nothing of an earlier attempt is mistaken for a result: their
    // directories go (a frozen holder's run then fails to write, and its
    // finish is refused anyway), and so does anything published before the
    // job was queued again.
    discard_attempts(options_.jobs_dir, job.id, job.claim);
    std::filesystem::remove_all(options_.jobs_dir / job.id);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    // threads_per_job is this worker's share of the cores: a job's own
    // "threads" is kept below it, else a trial of a few steps picks up to it
    // (run/thread_trial.hpp).
    const int offered = offer_threads(held);
    PreparedJob prepared = [&] {
      SetupProgressScope setup([&](const SetupStatus& s) {
        hub_.publish(job.id, "progress", setup_document(job.id, job.steps, s).dump());
      });
      return prepare_job(nlohmann::json::parse(job.job_json), 0, offered);
    }();
    if (options_.core_budget > 0) {
      // Hand back the cores the job is not worth (its size, or its trial's most).
      int spare = held - std::max({1, prepared.scene.sim.threads, prepared.trial_threads});
      held -= spare;
      release_cores(spare);
    }
    a.steps = prepared.steps;
    Observer observer(*this, rj);
    ExecuteOptions eo;
    eo.threads = options_.threads_per_job;
    eo.observer = &observer;
    const RunResult r = execute_prepared(prepared, dir, eo).run;
    a.last.step = r.steps_done;
    a.last.simulated_s = prepared.scene.sim.time;
    a.last.wall_s = r.wall_s;
    a.last.progress = percent(r.steps_done, prepared.steps);
    const FeOutcome fe = rj.fe ? fe_outcome(r.summary, r.status, rj.fe_estimate) : FeOutcome{};
    if (rj.fe) {
      a.last.wall_s += fe.wall_s;
      a.last.fe_check_json = fe.document.dump();
    }
    if (r.status == "completed" && rj.fe && !fe.ok && observer.cancelled()) {
      // The check was stopped, not failed: the job as a whole is.
      a.cancelled = true;
    } else if (r.status == "completed") {
      a.outcome = JobStatus::successful;
      a.last.progress = 100;
      a.message =
          "completed " + std::to_string(r.steps_done) + " steps in " + fixed(r.wall_s, 2) + " s";
      if (rj.fe) a.message += "; " + fe.sentence;
    } else if (r.status == "cancelled") {
      a.cancelled = true;
    } else {
      a.message = "the run diverged: " + r.message;
    }
  } catch (const InvalidJob& e) {
    a.message = std::string("the job cannot run: ") + e.what();
  } catch (const std::exception& e) {
    a.message = std::string("internal error: ") + e.what();
  }
  return a;
}

void WorkerPool::record(const JobRecord& job, const RunningJob& rj,
                        const std::filesystem::path& dir, const Attempt& a) {
  const std::string where =
      "step " + std::to_string(a.last.step) + " of " + std::to_string(a.steps);
  const char* log = options_.log_name.c_str();
  bool published = false;
  auto record_outcome = [&] {
    if (a.cancelled && !rj.dismissed && !rj.lost && stopping_) {
      ++counters().requeues;
      store_.requeue(job.id,
                     "re-queued: the server was stopped while this job ran (at " + where +
                         "); it starts again from the beginning when the server is back",
                     job.claim);
    } else if (a.cancelled) {
      // Dismissed: this run's files go before the job says it stopped, so
      // that a client who reads that finds none left.
      std::error_code gone;
      std::filesystem::remove_all(dir, gone);
      if (!store_.close_dismissed(job.id, "dismissed while running; the run stopped at " + where,
                                  a.last) &&
          rj.lost) {
        ++counters().claims_lost;
        log_line(LogLevel::warning,
                 "%s: job %s stopped at %s: its claim was lost (its lease ran out and another "
                 "worker claimed it, or it ended); this run's files were discarded\n",
                 log, job.id.c_str(), where.c_str());
      }
    } else if (store_.finish(job.id, a.outcome, a.message, a.last, job.claim)) {
      published = true;
    } else if (!store_.close_dismissed(
                   job.id,
                   "dismissed while running; the run had just " +
                       std::string(a.outcome == JobStatus::successful ? "completed" : "failed"),
                   a.last)) {
      ++counters().claims_lost;
      log_line(LogLevel::warning,
               "%s: job %s: this run %s, but its claim was lost meanwhile (another worker "
               "claimed the job after the lease ran out); the other run's outcome stands and "
               "this run's files were discarded\n",
               log, job.id.c_str(), a.outcome == JobStatus::successful ? "completed" : "failed");
    }
  };
  // A shared store may be down: a finished run is kept until its outcome is
  // recorded, or until the store says another claim has the job (then
  // finish is refused above). Only a stopping process gives up, and says so.
  for (auto pause = std::chrono::milliseconds(250);;
       pause = std::min(pause * 2, std::chrono::milliseconds(1000))) {
    try {
      record_outcome();
      break;
    } catch (const std::exception& e) {
      if (options_.holder.lease_s <= 0 || stopping_) {
        log_line(LogLevel::warning,
                 "%s: job %s: its outcome could not be recorded (%s); its files stay in %s "
                 "and the job runs again once its lease has run out\n",
                 log, job.id.c_str(), e.what(), dir.string().c_str());
        throw;
      }
      ++counters().store_retries;
      log_line(LogLevel::warning, "%s: job %s: recording its outcome failed (%s); trying again\n",
               log, job.id.c_str(), e.what());
      std::this_thread::sleep_for(pause);
    }
  }
  if (published) {
    try {
      publish_attempt(options_.jobs_dir, job.id, job.claim);
    } catch (const std::exception& e) {
      // Recorded but not renamed: the API publishes it when first asked.
      log_line(LogLevel::warning, "%s: job %s: publishing its files failed: %s\n", log,
               job.id.c_str(), e.what());
    }
  } else {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
}

void WorkerPool::run(const JobRecord& job, int& held) {
  auto rj = std::make_shared<RunningJob>();
  rj->id = job.id;
  rj->claim = job.claim;
  rj->progress.steps = job.steps;
  rj->progress.end_s = job.end_s;
  rj->fe = runs_fe_check(nlohmann::json::parse(job.job_json, nullptr, false));
  if (rj->fe) {
    try {
      rj->fe_estimate = estimate_fe_stage(store_);
    } catch (const std::exception&) {
      // The store away: the fallback figure will do for an estimate.
    }
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    running_[job.id] = rj;
  }
  // Out of the running set however this ends (even if the store fails).
  struct Unregister {
    WorkerPool& pool;
    const std::string& id;
    ~Unregister() {
      std::lock_guard<std::mutex> lock(pool.mutex_);
      pool.running_.erase(id);
    }
  } unregister{*this, job.id};
  log_line(LogLevel::info, "%s: job %s running (%s, attempt %d)\n", options_.log_name.c_str(),
           job.id.c_str(), job.name.c_str(), job.attempts);
  publish_status(job.id);

  // This claim's own directory: published as the job's only once its
  // finish is recorded under this claim (attempt_dirs.hpp).
  const std::filesystem::path dir = attempt_dir(options_.jobs_dir, job.id, job.claim);
  record(job, *rj, dir, attempt(job, *rj, dir, held));
  const char* log = options_.log_name.c_str();
  const auto stored = store_.job(job.id);
  if (stored && stored->status == JobStatus::dismissed) {
    // Dismissed while it ran: whatever was published goes too.
    std::error_code ec;
    std::filesystem::remove_all(options_.jobs_dir / job.id, ec);
  }
  log_line(LogLevel::info, "%s: job %s %s: %s\n", log, job.id.c_str(),
           stored ? std::string(to_string(stored->status)).c_str() : "?",
           stored ? stored->message.c_str() : "");
  publish_status(job.id);
}

void WorkerPool::publish_status(const std::string& id) {
  const auto record = store_.job(id);
  if (!record) return;
  hub_.publish(id, "status", status_document(*record, live(id)).dump(),
               is_terminal_status(record->status));
}

void WorkerPool::flush() {
  std::vector<ProgressUpdate> batch;
  // id and event: the FE stages' progress, which they report seldom.
  std::vector<std::pair<std::string, std::string>> events;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& [id, job] : running_) {
      std::lock_guard<std::mutex> job_lock(job->mutex);
      const bool fe_stage = job->stage == "fe_check";
      if (!job->dirty && !fe_stage) continue;
      job->dirty = false;
      batch.push_back(live_update(*job));
      if (fe_stage) {
        events.emplace_back(
            id, progress_document(batch.back(), job->progress.steps, job->progress.end_s).dump());
      }
    }
  }
  for (const auto& [id, e] : events) hub_.publish(id, "progress", e);
  if (batch.empty()) return;
  try {
    // Jobs no longer running in the store were dismissed (perhaps by
    // another process sharing it): stop their runs.
    for (const std::string& id : store_.save_progress(batch)) cancel(id);
  } catch (const std::exception& e) {
    log_line(LogLevel::warning, "%s: storing progress failed: %s\n", options_.log_name.c_str(),
             e.what());
  }
}

void WorkerPool::heartbeat() {
  if (options_.holder.lease_s <= 0) return;
  std::vector<HeldJob> held;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [id, job] : running_) held.push_back({id, job->claim});
  }
  try {
    if (options_.workers > 0) {  // an API node without workers is no worker
      store_.worker_seen(options_.holder.worker, static_cast<int>(held.size()));
    }
    const std::vector<std::string> lost = store_.renew(options_.holder, held);
    std::lock_guard<std::mutex> lock(mutex_);
    for (const std::string& id : lost) {
      const auto it = running_.find(id);
      if (it != running_.end()) it->second->lost = true;
    }
  } catch (const std::exception& e) {
    // The runs go on: unrenewed for a whole lease, a claim may pass to
    // another worker, but only the claim that holds at the finish publishes
    // (attempt_dirs.hpp), and a run the store comes back to unclaimed keeps
    // its work.
    log_line(LogLevel::warning, "%s: renewing the leases failed: %s\n", options_.log_name.c_str(),
             e.what());
  }
}

void WorkerPool::reclaim() {
  {
    // Once per half lease and process is plenty.
    std::lock_guard<std::mutex> lock(reclaim_mutex_);
    const auto now = Clock::now();
    if (now - last_reclaim_ < std::chrono::duration<double>(options_.holder.lease_s / 2)) return;
    last_reclaim_ = now;
  }
  const Recovery r = store_.reclaim_expired(options_.max_attempts);
  counters().lease_expiries += static_cast<std::int64_t>(r.requeued.size());
  counters().lease_failures += static_cast<std::int64_t>(r.failed.size());
  for (const std::string& id : r.failed) discard_attempts(options_.jobs_dir, id);
  for (const std::string& id : r.requeued) {
    log_line(LogLevel::warning,
             "%s: job %s: its worker stopped renewing its lease; it is queued again\n",
             options_.log_name.c_str(), id.c_str());
  }
  for (const std::string& id : r.failed) {
    log_line(LogLevel::warning,
             "%s: job %s: its worker stopped renewing its lease %d times; it failed\n",
             options_.log_name.c_str(), id.c_str(), options_.max_attempts);
  }
}

void WorkerPool::flusher() {
  for (;;) {
    bool stop = false;
    {
      std::unique_lock<std::mutex> lock(flush_mutex_);
      flush_wake_.wait_for(lock, options_.flush_interval, [&] { return flusher_stop_; });
      stop = flusher_stop_;
    }
    flush();
    heartbeat();
    if (stop) return;
  }
}

}  // namespace gearsph::server
