// JobStore on PostgreSQL: one database shared by any number of API nodes
// and worker processes. Claims are one statement each
// (SELECT ... FOR UPDATE SKIP LOCKED inside the UPDATE), so workers never
// wait for each other and never get the same job; claims carry a lease on
// the database's clock, renewed by the workers' heartbeat. The schema has a
// version table; migrations run under an advisory lock, so processes
// starting together migrate once.
#include <algorithm>
#include <array>
#include <set>
#include <string>

#include "server/job_store.hpp"

#ifdef GEARSPH_WITH_POSTGRESQL
#include "server/postgres.hpp"
#endif

namespace gearsph::server {

#ifndef GEARSPH_WITH_POSTGRESQL

std::unique_ptr<JobStore> open_postgres_job_store(const std::string&) {
  throw std::runtime_error(
      "this gearsph was built without PostgreSQL (install libpq-dev and build again)");
}

#else

namespace {

using postgres::param;
using postgres::Params;

// ISO 8601 UTC with milliseconds, as the SQLite store writes them, computed
// by the database so every node agrees.
#define GEARSPH_NOW \
  "to_char(clock_timestamp() AT TIME ZONE 'UTC', 'YYYY-MM-DD\"T\"HH24:MI:SS.MS\"Z\"')"

// Migration i brings the schema from version i to i + 1. Append, never edit.
const std::array<const char*, 1> kMigrations = {
    R"sql(
CREATE TABLE studies (
  seq       BIGSERIAL PRIMARY KEY,
  id        TEXT NOT NULL UNIQUE,
  name      TEXT NOT NULL,
  spec_json TEXT NOT NULL,
  created   TEXT NOT NULL
);
CREATE TABLE jobs (
  seq             BIGSERIAL PRIMARY KEY,
  id              TEXT NOT NULL UNIQUE,
  status          TEXT NOT NULL
                  CHECK (status IN ('accepted','running','successful','failed','dismissed')),
  name            TEXT NOT NULL,
  job_json        TEXT NOT NULL,
  study_id        TEXT REFERENCES studies(id),
  study_index     BIGINT NOT NULL DEFAULT 0,
  parameters_json TEXT NOT NULL DEFAULT '{}',
  particles       BIGINT NOT NULL DEFAULT 0 CHECK (particles >= 0),
  steps           BIGINT NOT NULL DEFAULT 0 CHECK (steps >= 0),
  end_s           DOUBLE PRECISION NOT NULL DEFAULT 0,
  step            BIGINT NOT NULL DEFAULT 0 CHECK (step >= 0),
  simulated_s     DOUBLE PRECISION NOT NULL DEFAULT 0,
  wall_s          DOUBLE PRECISION NOT NULL DEFAULT 0,
  eta_s           DOUBLE PRECISION NOT NULL DEFAULT 0,
  progress        INTEGER NOT NULL DEFAULT 0 CHECK (progress BETWEEN 0 AND 100),
  attempts        INTEGER NOT NULL DEFAULT 0 CHECK (attempts >= 0),
  message         TEXT NOT NULL DEFAULT '',
  created         TEXT NOT NULL,
  started         TEXT,
  finished        TEXT,
  updated         TEXT NOT NULL,
  worker          TEXT,
  lease_until     TIMESTAMPTZ,
  dispatch_ref    TEXT,
  CHECK (status <> 'running' OR started IS NOT NULL),
  CHECK (status NOT IN ('successful','failed') OR finished IS NOT NULL)
);
CREATE INDEX jobs_by_status ON jobs(status, seq);
CREATE INDEX jobs_by_study ON jobs(study_id, study_index);
CREATE INDEX jobs_by_updated ON jobs(updated);
CREATE INDEX jobs_by_dispatch ON jobs(dispatch_ref) WHERE dispatch_ref IS NOT NULL;
CREATE TABLE idempotency_keys (
  scope     TEXT NOT NULL,
  key       TEXT NOT NULL,
  request   TEXT NOT NULL,
  target_id TEXT NOT NULL,
  created   TEXT NOT NULL,
  PRIMARY KEY (scope, key)
);
)sql",
};

// Any fixed number: the advisory lock that serialises migrations.
constexpr const char* kMigrationLock = "7146301";

const char* const kJobColumns =
    "id, status, name, job_json, study_id, study_index, parameters_json, particles, steps, "
    "end_s, step, simulated_s, wall_s, eta_s, progress, attempts, message, created, started, "
    "finished, updated, worker, dispatch_ref";

JobRecord read_job(const postgres::Result& r, int row) {
  JobRecord j;
  j.id = r.text(row, 0);
  j.status = r.text(row, 1);
  j.name = r.text(row, 2);
  j.job_json = r.text(row, 3);
  j.study_id = r.text(row, 4);
  j.study_index = r.int64(row, 5);
  j.parameters_json = r.text(row, 6);
  j.particles = r.int64(row, 7);
  j.steps = r.int64(row, 8);
  j.end_s = r.real(row, 9);
  j.step = r.int64(row, 10);
  j.simulated_s = r.real(row, 11);
  j.wall_s = r.real(row, 12);
  j.eta_s = r.real(row, 13);
  j.progress = static_cast<int>(r.int64(row, 14));
  j.attempts = static_cast<int>(r.int64(row, 15));
  j.message = r.text(row, 16);
  j.created = r.text(row, 17);
  j.started = r.text(row, 18);
  j.finished = r.text(row, 19);
  j.updated = r.text(row, 20);
  j.worker = r.text(row, 21);
  j.dispatch_ref = r.text(row, 22);
  return j;
}

std::vector<JobRecord> read_jobs(const postgres::Result& r) {
  std::vector<JobRecord> out;
  for (int i = 0; i < r.rows(); ++i) out.push_back(read_job(r, i));
  return out;
}

// A text[] literal of ids (UUIDs: no quoting needed beyond the braces).
std::string array_literal(const std::vector<std::string>& ids) {
  std::string s = "{";
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (i) s += ',';
    s += '"' + ids[i] + '"';
  }
  return s + "}";
}

const std::string kSelectJob = std::string("SELECT ") + kJobColumns + " FROM jobs";

class PostgresJobStore : public JobStore {
 public:
  explicit PostgresJobStore(const std::string& uri) : pool_(uri) { migrate(); }

  SubmitResult submit(const NewJob& job, const std::optional<Idempotency>& idem) override {
    auto db = pool_.acquire();
    postgres::Transaction tx(*db);
    if (auto seen = claim_key(*db, idem, job.id)) return *seen;
    insert_job(*db, job);
    tx.commit();
    return {SubmitResult::Kind::created, job.id};
  }

  SubmitResult submit_study(const NewStudy& study, const std::vector<NewJob>& jobs,
                            const std::optional<Idempotency>& idem) override {
    auto db = pool_.acquire();
    postgres::Transaction tx(*db);
    if (auto seen = claim_key(*db, idem, study.id)) return *seen;
    db->exec("INSERT INTO studies (id, name, spec_json, created) VALUES ($1, $2, $3, " GEARSPH_NOW
             ")",
             {param(study.id), param(study.name), param(study.spec_json)});
    for (const NewJob& j : jobs) insert_job(*db, j);
    tx.commit();
    return {SubmitResult::Kind::created, study.id};
  }

  std::optional<JobRecord> job(const std::string& id) override {
    auto db = pool_.acquire();
    const auto r = db->exec(kSelectJob + " WHERE id = $1", {param(id)});
    if (r.rows() == 0) return std::nullopt;
    return read_job(r, 0);
  }

  JobPage jobs(const JobQuery& q) override {
    std::string where = " WHERE TRUE";
    Params params;
    if (!q.statuses.empty()) {
      params.push_back(array_literal(q.statuses));
      where += " AND status = ANY($" + std::to_string(params.size()) + "::text[])";
    }
    if (!q.study_id.empty()) {
      params.push_back(q.study_id);
      where += " AND study_id = $" + std::to_string(params.size());
    }
    if (!q.created_from.empty()) {
      params.push_back(q.created_from);
      where += " AND created >= $" + std::to_string(params.size());
    }
    if (!q.created_to.empty()) {
      params.push_back(q.created_to);
      where += " AND created <= $" + std::to_string(params.size());
    }
    if (q.min_wall_s >= 0) {
      params.push_back(param(q.min_wall_s));
      where += " AND wall_s >= $" + std::to_string(params.size()) + "::double precision";
    }
    if (q.max_wall_s >= 0) {
      params.push_back(param(q.max_wall_s));
      where += " AND wall_s <= $" + std::to_string(params.size()) + "::double precision";
    }
    auto db = pool_.acquire();
    JobPage page;
    {
      const auto r = db->exec("SELECT COUNT(*) FROM jobs" + where, params);
      page.total = r.int64(0, 0);
    }
    const std::string order = q.study_id.empty() ? " ORDER BY seq DESC" : " ORDER BY study_index";
    params.push_back(param(q.limit));
    params.push_back(param(q.offset));
    const auto r =
        db->exec(kSelectJob + where + order + " LIMIT $" + std::to_string(params.size() - 1) +
                     " OFFSET $" + std::to_string(params.size()),
                 params);
    page.jobs = read_jobs(r);
    return page;
  }

  std::optional<StudyRecord> study(const std::string& id) override {
    auto db = pool_.acquire();
    const auto r =
        db->exec("SELECT id, name, spec_json, created FROM studies WHERE id = $1", {param(id)});
    if (r.rows() == 0) return std::nullopt;
    return StudyRecord{r.text(0, 0), r.text(0, 1), r.text(0, 2), r.text(0, 3)};
  }

  std::map<std::string, std::int64_t> count_by_status() override {
    std::map<std::string, std::int64_t> counts{
        {"accepted", 0}, {"running", 0}, {"successful", 0}, {"failed", 0}, {"dismissed", 0}};
    auto db = pool_.acquire();
    const auto r = db->exec("SELECT status, COUNT(*) FROM jobs GROUP BY status");
    for (int i = 0; i < r.rows(); ++i) counts[r.text(i, 0)] = r.int64(i, 1);
    return counts;
  }

  std::optional<JobRecord> claim(const Holder& holder) override {
    auto db = pool_.acquire();
    // One statement; SKIP LOCKED: a job another worker is claiming right now
    // is passed over instead of waited for.
    const auto r = db->exec(
        "UPDATE jobs SET status = 'running', attempts = attempts + 1, "
        "message = 'running' || CASE WHEN attempts > 0 THEN ' (attempt ' || (attempts + 1) || "
        "')' ELSE '' END, started = " GEARSPH_NOW ", updated = " GEARSPH_NOW
        ", finished = NULL, step = 0, simulated_s = 0, wall_s = 0, eta_s = 0, progress = 0, "
        "worker = $1, lease_until = CASE WHEN $2::float8 > 0 THEN clock_timestamp() + "
        "$2::float8 * interval '1 second' ELSE NULL END "
        "WHERE seq = (SELECT seq FROM jobs WHERE status = 'accepted' AND dispatch_ref IS NULL "
        "ORDER BY seq LIMIT 1 FOR UPDATE SKIP LOCKED) RETURNING " +
            std::string(kJobColumns),
        {param(holder.worker), param(holder.lease_s)});
    if (r.rows() == 0) return std::nullopt;
    return read_job(r, 0);
  }

  std::vector<std::string> renew(const Holder& holder,
                                 const std::vector<std::string>& ids) override {
    if (ids.empty()) return {};
    auto db = pool_.acquire();
    const auto r = db->exec(
        "UPDATE jobs SET lease_until = clock_timestamp() + $2::float8 * interval '1 second' "
        "WHERE id = ANY($1::text[]) AND status = 'running' AND worker = $3 RETURNING id",
        {array_literal(ids), param(holder.lease_s), param(holder.worker)});
    std::set<std::string> held;
    for (int i = 0; i < r.rows(); ++i) held.insert(r.text(i, 0));
    std::vector<std::string> lost;
    for (const std::string& id : ids) {
      if (!held.count(id)) lost.push_back(id);
    }
    return lost;
  }

  Recovery reclaim_expired(int max_attempts) override {
    Recovery out;
    auto db = pool_.acquire();
    postgres::Transaction tx(*db);
    {
      const auto r = db->exec(
          "UPDATE jobs SET status = 'failed', eta_s = 0, lease_until = NULL, message = "
          "'its worker ' || worker || ' stopped renewing its lease during attempt ' || attempts "
          "|| '; not started again after ' || attempts || CASE WHEN attempts = 1 THEN "
          "' attempt' ELSE ' attempts' END, finished = " GEARSPH_NOW ", updated = " GEARSPH_NOW
          " WHERE status = 'running' AND lease_until < clock_timestamp() AND attempts >= $1 "
          "RETURNING id",
          {param(max_attempts)});
      for (int i = 0; i < r.rows(); ++i) out.failed.push_back(r.text(i, 0));
    }
    {
      const auto r = db->exec(
          "UPDATE jobs SET status = 'accepted', lease_until = NULL, message = 're-queued: its "
          "worker ' || worker || ' stopped renewing its lease during attempt ' || attempts || "
          "'; the job starts again from the beginning', started = NULL, step = 0, "
          "simulated_s = 0, wall_s = 0, eta_s = 0, progress = 0, updated = " GEARSPH_NOW
          " WHERE status = 'running' AND lease_until < clock_timestamp() RETURNING id");
      for (int i = 0; i < r.rows(); ++i) out.requeued.push_back(r.text(i, 0));
    }
    tx.commit();
    return out;
  }

  std::vector<std::string> save_progress(const std::vector<ProgressUpdate>& batch) override {
    std::vector<std::string> gone;
    if (batch.empty()) return gone;
    auto db = pool_.acquire();
    postgres::Transaction tx(*db);
    for (const ProgressUpdate& u : batch) {
      const auto r = db->exec(
          "UPDATE jobs SET step = $1, simulated_s = $2, wall_s = $3, eta_s = $4, progress = $5, "
          "updated = " GEARSPH_NOW " WHERE id = $6 AND status = 'running'",
          {param(u.step), param(u.simulated_s), param(u.wall_s), param(u.eta_s), param(u.progress),
           param(u.id)});
      if (r.affected() == 0) gone.push_back(u.id);
    }
    tx.commit();
    return gone;
  }

  bool finish(const std::string& id, const std::string& status, const std::string& message,
              const ProgressUpdate& last, const std::string& worker) override {
    auto db = pool_.acquire();
    const auto r = db->exec(
        "UPDATE jobs SET status = $1, message = $2, step = $3, simulated_s = $4, wall_s = $5, "
        "eta_s = 0, progress = $6, lease_until = NULL, dispatch_ref = NULL, "
        "finished = " GEARSPH_NOW ", updated = " GEARSPH_NOW
        " WHERE id = $7 AND status = 'running' AND ($8 = '' OR worker = $8)",
        {param(status), param(message), param(last.step), param(last.simulated_s),
         param(last.wall_s), param(last.progress), param(id), param(worker)});
    return r.affected() > 0;
  }

  bool close_dismissed(const std::string& id, const std::string& message,
                       const ProgressUpdate& last) override {
    auto db = pool_.acquire();
    const auto r = db->exec(
        "UPDATE jobs SET message = $1, step = $2, simulated_s = $3, wall_s = $4, eta_s = 0, "
        "progress = $5, lease_until = NULL, finished = " GEARSPH_NOW ", updated = " GEARSPH_NOW
        " WHERE id = $6 AND status = 'dismissed'",
        {param(message), param(last.step), param(last.simulated_s), param(last.wall_s),
         param(last.progress), param(id)});
    return r.affected() > 0;
  }

  bool requeue(const std::string& id, const std::string& message,
               const std::string& worker) override {
    auto db = pool_.acquire();
    const auto r = db->exec(
        "UPDATE jobs SET status = 'accepted', attempts = GREATEST(attempts - 1, 0), "
        "message = $1, started = NULL, step = 0, simulated_s = 0, wall_s = 0, eta_s = 0, "
        "progress = 0, lease_until = NULL, updated = " GEARSPH_NOW
        " WHERE id = $2 AND status = 'running' AND ($3 = '' OR worker = $3)",
        {param(message), param(id), param(worker)});
    return r.affected() > 0;
  }

  std::optional<JobRecord> dismiss(const std::string& id) override {
    auto db = pool_.acquire();
    postgres::Transaction tx(*db);
    const auto r = db->exec(kSelectJob + " WHERE id = $1 FOR UPDATE", {param(id)});
    if (r.rows() == 0) return std::nullopt;
    JobRecord before = read_job(r, 0);
    if (before.status != "dismissed") {
      const std::string message =
          before.status == "accepted" ? "dismissed before it started"
          : before.status == "running"
              ? "dismissed while running; the run stops at its next check"
              : "dismissed after it had " +
                    std::string(before.status == "successful" ? "completed" : "failed") +
                    "; its files were deleted";
      db->exec(
          "UPDATE jobs SET status = 'dismissed', message = $1, eta_s = 0, finished = " GEARSPH_NOW
          ", updated = " GEARSPH_NOW " WHERE id = $2",
          {param(message), param(id)});
    }
    tx.commit();
    return before;
  }

  Recovery recover(int max_attempts) override {
    Recovery out;
    auto db = pool_.acquire();
    postgres::Transaction tx(*db);
    {
      const auto r = db->exec(
          "UPDATE jobs SET status = 'failed', eta_s = 0, message = 'interrupted ' || attempts || "
          "CASE WHEN attempts = 1 THEN ' time' ELSE ' times' END || ' (the server stopped while "
          "it ran); not started again after ' || attempts || CASE WHEN attempts = 1 THEN "
          "' attempt' ELSE ' attempts' END, finished = " GEARSPH_NOW ", updated = " GEARSPH_NOW
          " WHERE status = 'running' AND lease_until IS NULL AND dispatch_ref IS NULL "
          "AND attempts >= $1 RETURNING id",
          {param(max_attempts)});
      for (int i = 0; i < r.rows(); ++i) out.failed.push_back(r.text(i, 0));
    }
    {
      const auto r = db->exec(
          "UPDATE jobs SET status = 'accepted', message = 're-queued: the server stopped while "
          "attempt ' || attempts || ' ran; the job starts again from the beginning', "
          "started = NULL, step = 0, simulated_s = 0, wall_s = 0, eta_s = 0, progress = 0, "
          "updated = " GEARSPH_NOW
          " WHERE status = 'running' AND lease_until IS NULL AND dispatch_ref IS NULL "
          "RETURNING id");
      for (int i = 0; i < r.rows(); ++i) out.requeued.push_back(r.text(i, 0));
    }
    tx.commit();
    return out;
  }

  std::optional<JobRecord> claim_for_dispatch(const std::string& ref) override {
    auto db = pool_.acquire();
    const auto r = db->exec(
        "UPDATE jobs SET dispatch_ref = $1, updated = " GEARSPH_NOW
        " WHERE seq = (SELECT seq FROM jobs WHERE status = 'accepted' AND dispatch_ref IS NULL "
        "ORDER BY seq LIMIT 1 FOR UPDATE SKIP LOCKED) RETURNING " +
            std::string(kJobColumns),
        {param(ref)});
    if (r.rows() == 0) return std::nullopt;
    return read_job(r, 0);
  }

  std::vector<JobRecord> dispatched() override {
    auto db = pool_.acquire();
    return read_jobs(db->exec(kSelectJob + " WHERE dispatch_ref IS NOT NULL ORDER BY seq"));
  }

  bool set_dispatch(const std::string& id, const std::string& status, const std::string& ref,
                    const std::string& message) override {
    auto db = pool_.acquire();
    const auto r =
        db->exec("UPDATE jobs SET dispatch_ref = $1, message = $2, updated = " GEARSPH_NOW
                 " WHERE id = $3 AND status = $4 AND dispatch_ref IS NOT NULL",
                 {param(ref), param(message), param(id), param(status)});
    return r.affected() > 0;
  }

  bool release_dispatch(const std::string& id, const std::string& message) override {
    auto db = pool_.acquire();
    const auto r =
        db->exec("UPDATE jobs SET dispatch_ref = NULL, message = $1, updated = " GEARSPH_NOW
                 " WHERE id = $2 AND status = 'accepted'",
                 {param(message), param(id)});
    return r.affected() > 0;
  }

  bool start_dispatched(const std::string& id, const std::string& worker,
                        const std::string& message) override {
    auto db = pool_.acquire();
    const auto r = db->exec(
        "UPDATE jobs SET status = 'running', attempts = attempts + 1, worker = $1, message = $2, "
        "started = " GEARSPH_NOW ", updated = " GEARSPH_NOW
        ", finished = NULL, step = 0, simulated_s = 0, wall_s = 0, eta_s = 0, progress = 0 "
        "WHERE id = $3 AND status = 'accepted' AND dispatch_ref IS NOT NULL",
        {param(worker), param(message), param(id)});
    return r.affected() > 0;
  }

  void forget_dispatch(const std::string& id) override {
    auto db = pool_.acquire();
    db->exec(
        "UPDATE jobs SET dispatch_ref = NULL WHERE id = $1 AND status IN "
        "('successful', 'failed', 'dismissed')",
        {param(id)});
  }

  std::vector<JobRecord> active_or_changed_within(double seconds) override {
    auto db = pool_.acquire();
    return read_jobs(db->exec(
        kSelectJob +
            " WHERE status IN ('accepted', 'running') OR updated >= "
            "to_char((clock_timestamp() - $1::float8 * interval '1 second') AT TIME ZONE 'UTC', "
            "'YYYY-MM-DD\"T\"HH24:MI:SS.MS\"Z\"') ORDER BY seq",
        {param(std::max(0.0, seconds))}));
  }

 private:
  void migrate() {
    auto db = pool_.acquire();
    postgres::Transaction tx(*db);
    db->exec(std::string("SELECT pg_advisory_xact_lock(") + kMigrationLock + ")");
    db->exec("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)");
    std::int64_t version = 0;
    {
      const auto r = db->exec("SELECT version FROM schema_version");
      if (r.rows() > 0) {
        version = r.int64(0, 0);
      } else {
        db->exec("INSERT INTO schema_version (version) VALUES (0)");
      }
    }
    if (version > static_cast<std::int64_t>(kMigrations.size())) {
      throw std::runtime_error("the job database has schema version " + std::to_string(version) +
                               ", newer than this gearsph (" + std::to_string(kMigrations.size()) +
                               "); upgrade gearsph");
    }
    for (auto v = static_cast<std::size_t>(version); v < kMigrations.size(); ++v) {
      db->exec(kMigrations[v]);
      db->exec("UPDATE schema_version SET version = $1", {param(static_cast<std::int64_t>(v + 1))});
    }
    tx.commit();
  }

  // Records the key for `target`, or answers with what it was used for
  // before. ON CONFLICT waits for a concurrent insert of the same key, so two
  // API nodes given the same key at once agree on one job.
  static std::optional<SubmitResult> claim_key(postgres::Connection& db,
                                               const std::optional<Idempotency>& idem,
                                               const std::string& target) {
    if (!idem) return std::nullopt;
    const auto inserted = db.exec(
        "INSERT INTO idempotency_keys (scope, key, request, target_id, created) VALUES "
        "($1, $2, $3, $4, " GEARSPH_NOW ") ON CONFLICT (scope, key) DO NOTHING",
        {param(idem->scope), param(idem->key), param(idem->request), param(target)});
    if (inserted.affected() > 0) return std::nullopt;
    const auto r =
        db.exec("SELECT request, target_id FROM idempotency_keys WHERE scope = $1 AND key = $2",
                {param(idem->scope), param(idem->key)});
    const bool same = r.text(0, 0) == idem->request;
    return SubmitResult{same ? SubmitResult::Kind::existing : SubmitResult::Kind::conflict,
                        r.text(0, 1)};
  }

  static void insert_job(postgres::Connection& db, const NewJob& j) {
    db.exec(
        "INSERT INTO jobs (id, status, name, job_json, study_id, study_index, parameters_json, "
        "particles, steps, end_s, message, created, updated) VALUES ($1, 'accepted', $2, $3, $4, "
        "$5, $6, $7, $8, $9, 'queued', " GEARSPH_NOW ", " GEARSPH_NOW ")",
        {param(j.id), param(j.name), param(j.job_json),
         j.study_id.empty() ? postgres::Param() : param(j.study_id), param(j.study_index),
         param(j.parameters_json), param(j.particles), param(j.steps), param(j.end_s)});
  }

  postgres::Pool pool_;
};

#undef GEARSPH_NOW

}  // namespace

std::unique_ptr<JobStore> open_postgres_job_store(const std::string& uri) {
  return std::make_unique<PostgresJobStore>(uri);
}

#endif

}  // namespace gearsph::server
