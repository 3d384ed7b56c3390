#pragma once
// The durable record of every job: what was submitted, where it stands,
// what became of it. The interface is what the server and the workers need
// and nothing more, so another engine (PostgreSQL) can take the place of
// SQLite. Every state change is one atomic statement or transaction.
//
// Job life cycle (OGC API - Processes status codes):
//   accepted --claim--> running --finish--> successful | failed
//      |                  |  \--requeue (server stopping / crashed)--> accepted
//      +--dismiss--+------+--dismiss--> dismissed   (successful/failed too)
//
// Who runs a job: a worker claims it and holds it under a lease that its
// heartbeat renews (renew); a job whose lease ran out (the worker died or
// lost the store) goes back to the queue (reclaim_expired). Each claim
// draws a random token; renew, finish and requeue name it, so a holder
// that lost its claim (frozen, cut off, or a namesake in another PID
// namespace) can move the job no more. Until somebody claims the job
// again, its last holder may still record the outcome of its run. A worker with
// no lease (lease_s <= 0) is the single server's own pool, whose jobs are
// recovered at its start-up (recover). A job handed to an outside
// scheduler (Slurm) carries that scheduler's reference (dispatch_ref)
// while it is tracked.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace gearsph::server {

// The store cannot be reached (its server down or restarting, the
// connection lost, the file locked past the wait): the same request may
// succeed later. The API answers it with 503 and Retry-After.
class StoreUnavailable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class JobStatus { accepted, running, successful, failed, dismissed };
inline constexpr JobStatus kJobStatuses[] = {JobStatus::accepted, JobStatus::running,
                                             JobStatus::successful, JobStatus::failed,
                                             JobStatus::dismissed};
// As in documents and the database: "accepted", "running", ...
std::string_view to_string(JobStatus s);
std::optional<JobStatus> parse_job_status(std::string_view s);
bool is_job_status(std::string_view s);
bool is_terminal_status(JobStatus s);  // successful, failed, dismissed
// In JSON documents a status is its name, never its number.
NLOHMANN_JSON_SERIALIZE_ENUM(JobStatus, {{JobStatus::accepted, "accepted"},
                                         {JobStatus::running, "running"},
                                         {JobStatus::successful, "successful"},
                                         {JobStatus::failed, "failed"},
                                         {JobStatus::dismissed, "dismissed"}})

struct JobRecord {
  std::string id;
  JobStatus status = JobStatus::accepted;
  std::string name;
  std::string job_json;  // the job with every default filled in: what runs
  std::string study_id;  // "" unless created by a study
  std::int64_t study_index = 0;
  std::string parameters_json = "{}";  // the study's axis values for this job
  std::int64_t particles = 0;
  std::int64_t steps = 0;  // planned
  double end_s = 0.0;      // planned simulated time
  std::int64_t step = 0;   // reached
  double simulated_s = 0.0;
  double wall_s = 0.0;
  double eta_s = 0.0;
  int progress = 0;  // percent, 0-100
  int attempts = 0;  // times a worker started it
  std::string message;
  std::string created, started, finished, updated;  // ISO 8601 UTC; "" if not yet
  std::string worker;                               // who claimed it last ("" if nobody)
  std::string claim;          // the token of the last claim ("" if none): fences its holder
  std::string dispatch_ref;   // an outside scheduler's reference while tracked ("" if none)
  std::string stage;          // while running: "sph" or "fe_check" ("" if not known)
  std::string fe_check_json;  // the FE stage's outcome as a JSON object ("" if none yet)
};

struct NewJob {
  std::string id, name, job_json;
  std::string client;  // the submitter's address, for the queue quota ("" if not known)
  std::string study_id;
  std::int64_t study_index = 0;
  std::string parameters_json = "{}";
  std::int64_t particles = 0, steps = 0;
  double end_s = 0.0;
};

struct NewStudy {
  std::string id, name, spec_json;
};

struct StudyRecord {
  std::string id, name, spec_json, created;
};

// A client's Idempotency-Key and the request it came with (canonical JSON).
struct Idempotency {
  std::string scope;  // "jobs" or "studies"
  std::string key;
  std::string request;
};

struct SubmitResult {
  // queue_full, client_queue_full: refused by the QueueQuota; nothing stored.
  enum class Kind { created, existing, conflict, queue_full, client_queue_full };
  Kind kind = Kind::created;
  std::string id;           // of the new or existing job / study
  std::int64_t queued = 0;  // queue_full / client_queue_full: the queued jobs counted
};

// The queue quota (Limits::max_queued, max_queued_per_client), checked in
// the transaction that stores the jobs, so that concurrent submissions
// cannot overfill the queue between a count and an insert. 0: no limit.
struct QueueQuota {
  std::int64_t max_queued = 0;
  std::int64_t max_queued_per_client = 0;
  std::string client;  // whose share is counted (NewJob::client); "": none
};

struct JobQuery {
  std::vector<JobStatus> statuses;  // empty: any
  std::string study_id;             // non-empty: that study's jobs, in study order
  // Created within [created_from, created_to] (the store's ISO 8601 UTC
  // form, "" for an open end).
  std::string created_from, created_to;
  // A run's wall time wall_s (0 until it runs) within these bounds (< 0: none).
  double min_wall_s = -1, max_wall_s = -1;
  std::int64_t limit = 50;
  std::int64_t offset = 0;  // newest first, unless study_id is given
};

struct JobPage {
  std::vector<JobRecord> jobs;
  std::int64_t total = 0;  // matching the query, ignoring limit and offset
};

// A run's progress. With the FE check, progress, wall_s and eta_s count
// both stages (docs/api.md, The FE stage).
struct ProgressUpdate {
  ProgressUpdate() = default;
  ProgressUpdate(std::string id_, std::int64_t step_, double simulated_s_, double wall_s_,
                 double eta_s_, int progress_, std::string stage_ = {},
                 std::string fe_check_json_ = {})
      : id(std::move(id_)),
        step(step_),
        simulated_s(simulated_s_),
        wall_s(wall_s_),
        eta_s(eta_s_),
        progress(progress_),
        stage(std::move(stage_)),
        fe_check_json(std::move(fe_check_json_)) {}
  std::string id;
  std::int64_t step = 0;
  double simulated_s = 0.0, wall_s = 0.0, eta_s = 0.0;
  int progress = 0;
  std::string stage;          // "sph" or "fe_check"
  std::string fe_check_json;  // "" for a job without the FE check
};

// A claimant: "host:pid:random" of a worker process, or the server's own
// pool. lease_s > 0: its claims expire unless renewed within that many
// seconds.
struct Holder {
  std::string worker = "local";
  double lease_s = 0.0;
};

// A job as its holder knows it: the id and the token of its claim.
struct HeldJob {
  std::string id, claim;
};

// A fresh claim token: 128 random bits as hex.
std::string new_claim_token();

struct WorkerSeen {
  std::string name;
  double seen_ago_s = 0;
  int running = 0;
};

struct Durations {
  std::vector<double> bounds;
  std::vector<std::int64_t> at_most;  // cumulative counts, one per bound
  std::int64_t count = 0;
  double sum_s = 0;
};

struct Recovery {
  std::vector<std::string> requeued;  // interrupted runs that will start again
  std::vector<std::string> failed;    // interrupted max_attempts times
};

class JobStore {
 public:
  virtual ~JobStore() = default;

  // Stores an accepted job; with an idempotency key already used, answers
  // `existing` (same request) or `conflict` (another request); beyond the
  // quota, `queue_full` or `client_queue_full` and stores nothing.
  virtual SubmitResult submit(const NewJob& job, const std::optional<Idempotency>& idem,
                              const QueueQuota& quota) = 0;
  // A study and all its jobs, in one transaction.
  virtual SubmitResult submit_study(const NewStudy& study, const std::vector<NewJob>& jobs,
                                    const std::optional<Idempotency>& idem,
                                    const QueueQuota& quota) = 0;
  // Without a quota.
  SubmitResult submit(const NewJob& job, const std::optional<Idempotency>& idem) {
    return submit(job, idem, QueueQuota{});
  }
  SubmitResult submit_study(const NewStudy& study, const std::vector<NewJob>& jobs,
                            const std::optional<Idempotency>& idem) {
    return submit_study(study, jobs, idem, QueueQuota{});
  }

  virtual std::optional<JobRecord> job(const std::string& id) = 0;
  virtual JobPage jobs(const JobQuery& query) = 0;
  virtual std::optional<StudyRecord> study(const std::string& id) = 0;
  // Jobs by status name, every status present.
  virtual std::map<std::string, std::int64_t> count_by_status() = 0;
  // Queued (accepted) jobs submitted from `client` (NewJob::client).
  virtual std::int64_t queued_from(const std::string& client) = 0;

  // Oldest accepted job (not handed to a scheduler) -> running, attempts + 1,
  // held by `holder` under a new claim token (JobRecord::claim); nullopt if
  // none is queued. Two claimants never get the same job.
  virtual std::optional<JobRecord> claim(const Holder& holder) = 0;
  std::optional<JobRecord> claim() { return claim(Holder{}); }
  // Heartbeat: extends the lease of the `held` jobs whose claim is still
  // theirs: running, or queued again after the lease ran out while nobody
  // has claimed them since (those run again under the same claim). Returns
  // the ids of the others (dismissed, claimed by another, or ended): their
  // runs should stop.
  virtual std::vector<std::string> renew(const Holder& holder,
                                         const std::vector<HeldJob>& held) = 0;
  // Running jobs whose lease ran out go back to the queue, or fail once they
  // were started max_attempts times.
  virtual Recovery reclaim_expired(int max_attempts) = 0;
  // Progress of running jobs, in one transaction. Returns the ids that are
  // no longer running (dismissed meanwhile): their runs should stop.
  virtual std::vector<std::string> save_progress(const std::vector<ProgressUpdate>& batch) = 0;
  // running -> successful | failed; false if the job was not running. With
  // a `claim` token: only while the job is that claim's, running or queued
  // again with nobody having claimed it since (its lease ran out during a
  // store outage; the run's result is still the only one).
  virtual bool finish(const std::string& id, JobStatus status, const std::string& message,
                      const ProgressUpdate& last, const std::string& claim) = 0;
  bool finish(const std::string& id, JobStatus status, const std::string& message,
              const ProgressUpdate& last) {
    return finish(id, status, message, last, "");
  }
  // Records where a run dismissed while running stopped; false if the job is not dismissed.
  virtual bool close_dismissed(const std::string& id, const std::string& message,
                               const ProgressUpdate& last) = 0;
  // running -> accepted without counting the attempt (the server is
  // stopping); with a `claim` token only while the claim is still that one.
  virtual bool requeue(const std::string& id, const std::string& message,
                       const std::string& claim) = 0;
  bool requeue(const std::string& id, const std::string& message) {
    return requeue(id, message, "");
  }
  // Any state -> dismissed. Returns the record before the change, or nullopt if unknown.
  virtual std::optional<JobRecord> dismiss(const std::string& id) = 0;
  // At start-up: jobs the server's own pool left running (no lease, no
  // scheduler) go back to the queue, or fail once they were started
  // max_attempts times.
  virtual Recovery recover(int max_attempts) = 0;

  // An outside scheduler (Slurm). The oldest queued job not yet handed over
  // gets `ref` (a placeholder until the scheduler answers); its status stays
  // accepted. nullopt if none.
  virtual std::optional<JobRecord> claim_for_dispatch(const std::string& ref) = 0;
  // Every job that carries a dispatch reference.
  virtual std::vector<JobRecord> dispatched() = 0;
  // Compare and set: replaces the reference and the message of a dispatched
  // job, if it still has status `status` and the reference `expected`, and
  // (min_age_s > 0) has not changed for that many seconds by the store's
  // clock. Of two API nodes racing for one job, one wins.
  virtual bool set_dispatch(const std::string& id, JobStatus status, const std::string& expected,
                            const std::string& ref, const std::string& message,
                            double min_age_s = 0) = 0;
  // Handing over failed: the job is queued again, without a reference; with
  // the same conditions on the reference `expected` as set_dispatch.
  virtual bool release_dispatch(const std::string& id, const std::string& expected,
                                const std::string& message, double min_age_s = 0) = 0;
  // The scheduler started it: accepted -> running, attempts + 1.
  virtual bool start_dispatched(const std::string& id, const std::string& worker,
                                const std::string& message) = 0;
  // The scheduler put it back in its queue (a requeue, a preemption):
  // running -> accepted, progress from the start, the reference kept.
  virtual bool unstart_dispatched(const std::string& id, const std::string& ref,
                                  const std::string& message) = 0;
  // Drops the reference of a job that is finished or dismissed (after the
  // scheduler was told to cancel it).
  virtual void forget_dispatch(const std::string& id) = 0;

  // Operations (/metrics, retention). A worker process's heartbeat, with
  // the jobs it runs; the workers seen within `seconds`, with the seconds
  // since each was seen.
  virtual void worker_seen(const std::string& worker, int running) = 0;
  virtual std::vector<WorkerSeen> workers_seen(double seconds) = 0;

  // The dashboard's sessions (sessions.hpp), by the SHA-256 of their id:
  // a new one ending `lifetime_s` from now, the ended ones and, beyond
  // `max_sessions`, those ending first removed (how many open ones went);
  // whether one is open now; closing one (false if there was none); how
  // many are open.
  virtual std::int64_t open_session(const std::string& id_hash, double lifetime_s,
                                    std::int64_t max_sessions) = 0;
  virtual bool session_open(const std::string& id_hash) = 0;
  virtual bool close_session(const std::string& id_hash) = 0;
  virtual std::int64_t open_sessions() = 0;
  // How many ended jobs (successful or failed) ran at most each of `bounds`
  // seconds (cumulative, as a Prometheus histogram), their count and the
  // sum of their wall times.
  virtual Durations durations(const std::vector<double>& bounds) = 0;
  // Deletes jobs that ended (successful, failed, dismissed) more than
  // `seconds` ago, studies left without jobs and idempotency keys as old;
  // returns the ids of the jobs deleted (their directories go too).
  virtual std::vector<std::string> prune(double seconds) = 0;

  // Whether the store announces changes (PostgreSQL); then
  // wait_for_change waits up to `timeout` for one (true) or none (false).
  virtual bool notifies() const { return false; }
  virtual bool wait_for_change(std::chrono::milliseconds) { return false; }
  // Jobs changed within the last `seconds` (store clock), without their job
  // documents: what a watcher needs after its first look.
  virtual std::vector<JobRecord> changed_within(double seconds) = 0;

  // Jobs that are queued or running, or were changed within the last
  // `seconds` (by the store's clock): what a server that does not run the
  // jobs itself watches to publish their events.
  virtual std::vector<JobRecord> active_or_changed_within(double seconds) = 0;
};

namespace sql {
class Database;
}
// The store over an SQL engine (job_store_sql.cpp): its schema created or
// migrated, then the one life cycle above in that engine's dialect.
std::unique_ptr<JobStore> open_sql_job_store(std::unique_ptr<sql::Database> db);
// SQLite in WAL mode at `file` (created with its schema, migrated if older).
std::unique_ptr<JobStore> open_sqlite_job_store(const std::filesystem::path& file);
// PostgreSQL at a libpq connection URI (postgresql://user@host:port/db...),
// its schema created or migrated under an advisory lock. Throws if this
// build has no PostgreSQL client library or the server cannot be reached.
std::unique_ptr<JobStore> open_postgres_job_store(const std::string& uri);
// A store named on the command line: open_job_store.hpp.

}  // namespace gearsph::server
