// JobStore on SQLite: one file, WAL (readers never wait for the writer),
// busy timeout (writers wait for each other), a schema version table with
// ordered migrations, and CHECK constraints so no row can hold a state the
// life cycle does not know.
#include <algorithm>
#include <array>
#include <cstdio>
#include <string>

#include "server/job_store.hpp"
#include "server/sqlite.hpp"

namespace gearsph::server {

bool is_job_status(std::string_view s) {
  return s == "accepted" || s == "running" || s == "successful" || s == "failed" ||
         s == "dismissed";
}

bool is_terminal_status(std::string_view s) {
  return s == "successful" || s == "failed" || s == "dismissed";
}

namespace {

// ISO 8601 UTC with milliseconds, computed by SQLite so every writer agrees.
#define GEARSPH_NOW "strftime('%Y-%m-%dT%H:%M:%fZ','now')"
// Seconds since 1970 (leases), also from SQLite's clock.
#define GEARSPH_EPOCH "((julianday('now') - 2440587.5) * 86400.0)"

// Migration i brings the schema from version i to i + 1. Append, never edit.
const std::array<const char*, 2> kMigrations = {
    R"sql(
CREATE TABLE studies (
  seq       INTEGER PRIMARY KEY AUTOINCREMENT,
  id        TEXT NOT NULL UNIQUE,
  name      TEXT NOT NULL,
  spec_json TEXT NOT NULL,
  created   TEXT NOT NULL
);
CREATE TABLE jobs (
  seq             INTEGER PRIMARY KEY AUTOINCREMENT,
  id              TEXT NOT NULL UNIQUE,
  status          TEXT NOT NULL
                  CHECK (status IN ('accepted','running','successful','failed','dismissed')),
  name            TEXT NOT NULL,
  job_json        TEXT NOT NULL,
  study_id        TEXT REFERENCES studies(id),
  study_index     INTEGER NOT NULL DEFAULT 0,
  parameters_json TEXT NOT NULL DEFAULT '{}',
  particles       INTEGER NOT NULL DEFAULT 0 CHECK (particles >= 0),
  steps           INTEGER NOT NULL DEFAULT 0 CHECK (steps >= 0),
  end_s           REAL NOT NULL DEFAULT 0,
  step            INTEGER NOT NULL DEFAULT 0 CHECK (step >= 0),
  simulated_s     REAL NOT NULL DEFAULT 0,
  wall_s          REAL NOT NULL DEFAULT 0,
  eta_s           REAL NOT NULL DEFAULT 0,
  progress        INTEGER NOT NULL DEFAULT 0 CHECK (progress BETWEEN 0 AND 100),
  attempts        INTEGER NOT NULL DEFAULT 0 CHECK (attempts >= 0),
  message         TEXT NOT NULL DEFAULT '',
  created         TEXT NOT NULL,
  started         TEXT,
  finished        TEXT,
  updated         TEXT NOT NULL,
  CHECK (status <> 'running' OR started IS NOT NULL),
  CHECK (status NOT IN ('successful','failed') OR finished IS NOT NULL)
);
CREATE INDEX jobs_by_status ON jobs(status, seq);
CREATE INDEX jobs_by_study ON jobs(study_id, study_index);
CREATE TABLE idempotency_keys (
  scope     TEXT NOT NULL,
  key       TEXT NOT NULL,
  request   TEXT NOT NULL,
  target_id TEXT NOT NULL,
  created   TEXT NOT NULL,
  PRIMARY KEY (scope, key)
);
)sql",
    // 2: claims with leases (worker processes), outside schedulers (Slurm).
    R"sql(
ALTER TABLE jobs ADD COLUMN worker TEXT;
ALTER TABLE jobs ADD COLUMN lease_until REAL;
ALTER TABLE jobs ADD COLUMN dispatch_ref TEXT;
CREATE INDEX jobs_by_dispatch ON jobs(dispatch_ref) WHERE dispatch_ref IS NOT NULL;
)sql",
};

const char* const kJobColumns =
    "id, status, name, job_json, study_id, study_index, parameters_json, particles, steps, "
    "end_s, step, simulated_s, wall_s, eta_s, progress, attempts, message, created, started, "
    "finished, updated, worker, dispatch_ref";

JobRecord read_job(const sqlite::Statement& s) {
  JobRecord r;
  r.id = s.text(0);
  r.status = s.text(1);
  r.name = s.text(2);
  r.job_json = s.text(3);
  r.study_id = s.text(4);
  r.study_index = s.int64(5);
  r.parameters_json = s.text(6);
  r.particles = s.int64(7);
  r.steps = s.int64(8);
  r.end_s = s.real(9);
  r.step = s.int64(10);
  r.simulated_s = s.real(11);
  r.wall_s = s.real(12);
  r.eta_s = s.real(13);
  r.progress = static_cast<int>(s.int64(14));
  r.attempts = static_cast<int>(s.int64(15));
  r.message = s.text(16);
  r.created = s.text(17);
  r.started = s.text(18);
  r.finished = s.text(19);
  r.updated = s.text(20);
  r.worker = s.text(21);
  r.dispatch_ref = s.text(22);
  return r;
}

class SqliteJobStore : public JobStore {
 public:
  explicit SqliteJobStore(const std::filesystem::path& file) : pool_(file) { migrate(); }

  SubmitResult submit(const NewJob& job, const std::optional<Idempotency>& idem) override {
    auto db = pool_.acquire();
    sqlite::Transaction tx(*db);
    if (auto seen = check_key(*db, idem)) return *seen;
    insert_job(*db, job);
    remember_key(*db, idem, job.id);
    tx.commit();
    return {SubmitResult::Kind::created, job.id};
  }

  SubmitResult submit_study(const NewStudy& study, const std::vector<NewJob>& jobs,
                            const std::optional<Idempotency>& idem) override {
    auto db = pool_.acquire();
    sqlite::Transaction tx(*db);
    if (auto seen = check_key(*db, idem)) return *seen;
    db->prepare("INSERT INTO studies (id, name, spec_json, created) VALUES (?, ?, ?, " GEARSPH_NOW
                ")")
        .bind(1, study.id)
        .bind(2, study.name)
        .bind(3, study.spec_json)
        .run();
    for (const NewJob& j : jobs) insert_job(*db, j);
    remember_key(*db, idem, study.id);
    tx.commit();
    return {SubmitResult::Kind::created, study.id};
  }

  std::optional<JobRecord> job(const std::string& id) override {
    auto db = pool_.acquire();
    auto s = db->prepare(std::string("SELECT ") + kJobColumns + " FROM jobs WHERE id = ?");
    s.bind(1, id);
    if (!s.step()) return std::nullopt;
    return read_job(s);
  }

  JobPage jobs(const JobQuery& q) override {
    std::string where = " WHERE 1";
    if (!q.statuses.empty()) {
      where += " AND status IN (";
      for (std::size_t i = 0; i < q.statuses.size(); ++i) where += i ? ", ?" : "?";
      where += ")";
    }
    if (!q.study_id.empty()) where += " AND study_id = ?";
    if (!q.created_from.empty()) where += " AND created >= ?";
    if (!q.created_to.empty()) where += " AND created <= ?";
    if (q.min_wall_s >= 0) where += " AND wall_s >= ?";
    if (q.max_wall_s >= 0) where += " AND wall_s <= ?";
    auto bind_filters = [&](sqlite::Statement& s) {
      int n = 1;
      for (const std::string& st : q.statuses) s.bind(n++, st);
      if (!q.study_id.empty()) s.bind(n++, q.study_id);
      if (!q.created_from.empty()) s.bind(n++, q.created_from);
      if (!q.created_to.empty()) s.bind(n++, q.created_to);
      if (q.min_wall_s >= 0) s.bind(n++, q.min_wall_s);
      if (q.max_wall_s >= 0) s.bind(n++, q.max_wall_s);
      return n;
    };
    auto db = pool_.acquire();
    JobPage page;
    {
      auto s = db->prepare("SELECT COUNT(*) FROM jobs" + where);
      bind_filters(s);
      if (s.step()) page.total = s.int64(0);
    }
    auto s = db->prepare(std::string("SELECT ") + kJobColumns + " FROM jobs" + where +
                         (q.study_id.empty() ? " ORDER BY seq DESC" : " ORDER BY study_index") +
                         " LIMIT ? OFFSET ?");
    int n = bind_filters(s);
    s.bind(n++, q.limit);
    s.bind(n, q.offset);
    while (s.step()) page.jobs.push_back(read_job(s));
    return page;
  }

  std::optional<StudyRecord> study(const std::string& id) override {
    auto db = pool_.acquire();
    auto s = db->prepare("SELECT id, name, spec_json, created FROM studies WHERE id = ?");
    s.bind(1, id);
    if (!s.step()) return std::nullopt;
    return StudyRecord{s.text(0), s.text(1), s.text(2), s.text(3)};
  }

  std::map<std::string, std::int64_t> count_by_status() override {
    std::map<std::string, std::int64_t> counts{
        {"accepted", 0}, {"running", 0}, {"successful", 0}, {"failed", 0}, {"dismissed", 0}};
    auto db = pool_.acquire();
    auto s = db->prepare("SELECT status, COUNT(*) FROM jobs GROUP BY status");
    while (s.step()) counts[s.text(0)] = s.int64(1);
    return counts;
  }

  std::optional<JobRecord> claim(const Holder& holder) override {
    auto db = pool_.acquire();
    // One statement: two workers can never claim the same job.
    auto s = db->prepare(
        std::string("UPDATE jobs SET status = 'running', attempts = attempts + 1, "
                    "message = 'running' || CASE WHEN attempts > 0 THEN ' (attempt ' || "
                    "(attempts + 1) || ')' ELSE '' END, "
                    "started = " GEARSPH_NOW ", updated = " GEARSPH_NOW ", finished = NULL, "
                    "step = 0, simulated_s = 0, wall_s = 0, eta_s = 0, progress = 0, "
                    "worker = ?, lease_until = CASE WHEN ? > 0 THEN " GEARSPH_EPOCH
                    " + ? ELSE NULL END "
                    "WHERE seq = (SELECT seq FROM jobs WHERE status = 'accepted' "
                    "AND dispatch_ref IS NULL ORDER BY seq LIMIT 1) RETURNING ") +
        kJobColumns);
    s.bind(1, holder.worker).bind(2, holder.lease_s).bind(3, holder.lease_s);
    if (!s.step()) return std::nullopt;
    JobRecord r = read_job(s);
    s.run();
    return r;
  }

  std::vector<std::string> renew(const Holder& holder,
                                 const std::vector<std::string>& ids) override {
    std::vector<std::string> lost;
    if (ids.empty()) return lost;
    auto db = pool_.acquire();
    sqlite::Transaction tx(*db);
    for (const std::string& id : ids) {
      db->prepare("UPDATE jobs SET lease_until = " GEARSPH_EPOCH
                  " + ? WHERE id = ? AND status = 'running' AND worker = ?")
          .bind(1, holder.lease_s)
          .bind(2, id)
          .bind(3, holder.worker)
          .run();
      if (db->changes() == 0) lost.push_back(id);
    }
    tx.commit();
    return lost;
  }

  Recovery reclaim_expired(int max_attempts) override {
    Recovery out;
    auto db = pool_.acquire();
    sqlite::Transaction tx(*db);
    {
      auto s = db->prepare(
          "UPDATE jobs SET status = 'failed', eta_s = 0, lease_until = NULL, message = "
          "'its worker ' || worker || ' stopped renewing its lease during attempt ' || attempts "
          "|| '; not started again after ' || attempts || CASE WHEN attempts = 1 THEN "
          "' attempt' ELSE ' attempts' END, finished = " GEARSPH_NOW ", updated = " GEARSPH_NOW
          " WHERE status = 'running' AND lease_until < " GEARSPH_EPOCH
          " AND attempts >= ? RETURNING id");
      s.bind(1, max_attempts);
      while (s.step()) out.failed.push_back(s.text(0));
    }
    {
      auto s = db->prepare(
          "UPDATE jobs SET status = 'accepted', lease_until = NULL, message = 're-queued: its "
          "worker ' || worker || ' stopped renewing its lease during attempt ' || attempts || '; "
          "the job starts again from the beginning', started = NULL, step = 0, simulated_s = 0, "
          "wall_s = 0, eta_s = 0, progress = 0, updated = " GEARSPH_NOW
          " WHERE status = 'running' AND lease_until < " GEARSPH_EPOCH " RETURNING id");
      while (s.step()) out.requeued.push_back(s.text(0));
    }
    tx.commit();
    return out;
  }

  std::vector<std::string> save_progress(const std::vector<ProgressUpdate>& batch) override {
    std::vector<std::string> gone;
    if (batch.empty()) return gone;
    auto db = pool_.acquire();
    sqlite::Transaction tx(*db);
    for (const ProgressUpdate& u : batch) {
      db->prepare(
            "UPDATE jobs SET step = ?, simulated_s = ?, wall_s = ?, eta_s = ?, progress = ?, "
            "updated = " GEARSPH_NOW " WHERE id = ? AND status = 'running'")
          .bind(1, u.step)
          .bind(2, u.simulated_s)
          .bind(3, u.wall_s)
          .bind(4, u.eta_s)
          .bind(5, u.progress)
          .bind(6, u.id)
          .run();
      if (db->changes() == 0) gone.push_back(u.id);
    }
    tx.commit();
    return gone;
  }

  bool finish(const std::string& id, const std::string& status, const std::string& message,
              const ProgressUpdate& last, const std::string& worker) override {
    auto db = pool_.acquire();
    db->prepare(
          "UPDATE jobs SET status = ?, message = ?, step = ?, simulated_s = ?, wall_s = ?, "
          "eta_s = 0, progress = ?, lease_until = NULL, dispatch_ref = NULL, "
          "finished = " GEARSPH_NOW ", updated = " GEARSPH_NOW
          " WHERE id = ? AND status = 'running' AND (? = '' OR worker = ?)")
        .bind(1, status)
        .bind(2, message)
        .bind(3, last.step)
        .bind(4, last.simulated_s)
        .bind(5, last.wall_s)
        .bind(6, last.progress)
        .bind(7, id)
        .bind(8, worker)
        .bind(9, worker)
        .run();
    return db->changes() > 0;
  }

  bool close_dismissed(const std::string& id, const std::string& message,
                       const ProgressUpdate& last) override {
    auto db = pool_.acquire();
    db->prepare(
          "UPDATE jobs SET message = ?, step = ?, simulated_s = ?, wall_s = ?, eta_s = 0, "
          "progress = ?, lease_until = NULL, finished = " GEARSPH_NOW ", updated = " GEARSPH_NOW
          " WHERE id = ? AND status = 'dismissed'")
        .bind(1, message)
        .bind(2, last.step)
        .bind(3, last.simulated_s)
        .bind(4, last.wall_s)
        .bind(5, last.progress)
        .bind(6, id)
        .run();
    return db->changes() > 0;
  }

  bool requeue(const std::string& id, const std::string& message,
               const std::string& worker) override {
    auto db = pool_.acquire();
    db->prepare(
          "UPDATE jobs SET status = 'accepted', attempts = MAX(attempts - 1, 0), "
          "message = ?, started = NULL, step = 0, simulated_s = 0, wall_s = 0, eta_s = 0, "
          "progress = 0, lease_until = NULL, updated = " GEARSPH_NOW
          " WHERE id = ? AND status = 'running' AND (? = '' OR worker = ?)")
        .bind(1, message)
        .bind(2, id)
        .bind(3, worker)
        .bind(4, worker)
        .run();
    return db->changes() > 0;
  }

  std::optional<JobRecord> dismiss(const std::string& id) override {
    auto db = pool_.acquire();
    sqlite::Transaction tx(*db);
    auto s = db->prepare(std::string("SELECT ") + kJobColumns + " FROM jobs WHERE id = ?");
    s.bind(1, id);
    if (!s.step()) return std::nullopt;
    JobRecord before = read_job(s);
    if (before.status != "dismissed") {
      const std::string message =
          before.status == "accepted" ? "dismissed before it started"
          : before.status == "running"
              ? "dismissed while running; the run stops at its next check"
              : "dismissed after it had " +
                    std::string(before.status == "successful" ? "completed" : "failed") +
                    "; its files were deleted";
      db->prepare(
            "UPDATE jobs SET status = 'dismissed', message = ?, eta_s = 0, "
            "finished = " GEARSPH_NOW ", updated = " GEARSPH_NOW " WHERE id = ?")
          .bind(1, message)
          .bind(2, id)
          .run();
    }
    tx.commit();
    return before;
  }

  Recovery recover(int max_attempts) override {
    Recovery out;
    auto db = pool_.acquire();
    sqlite::Transaction tx(*db);
    {
      auto s = db->prepare(
          "UPDATE jobs SET status = 'failed', eta_s = 0, message = 'interrupted ' || attempts || "
          "CASE WHEN attempts = 1 THEN ' time' ELSE ' times' END || ' (the server stopped while "
          "it ran); not started again after ' || attempts || CASE WHEN attempts = 1 THEN "
          "' attempt' ELSE ' attempts' END, finished = " GEARSPH_NOW ", updated = " GEARSPH_NOW
          " WHERE status = 'running' AND lease_until IS NULL AND dispatch_ref IS NULL "
          "AND attempts >= ? RETURNING id");
      s.bind(1, max_attempts);
      while (s.step()) out.failed.push_back(s.text(0));
    }
    {
      auto s = db->prepare(
          "UPDATE jobs SET status = 'accepted', message = 're-queued: the server stopped while "
          "attempt ' || attempts || ' ran; the job starts again from the beginning', "
          "started = NULL, step = 0, simulated_s = 0, wall_s = 0, eta_s = 0, progress = 0, "
          "updated = " GEARSPH_NOW
          " WHERE status = 'running' AND lease_until IS NULL AND dispatch_ref IS NULL "
          "RETURNING id");
      while (s.step()) out.requeued.push_back(s.text(0));
    }
    tx.commit();
    return out;
  }

  std::optional<JobRecord> claim_for_dispatch(const std::string& ref) override {
    auto db = pool_.acquire();
    auto s = db->prepare(std::string("UPDATE jobs SET dispatch_ref = ?, updated = " GEARSPH_NOW
                                     " WHERE seq = (SELECT seq FROM jobs WHERE status = "
                                     "'accepted' AND dispatch_ref IS NULL ORDER BY seq LIMIT 1) "
                                     "RETURNING ") +
                         kJobColumns);
    s.bind(1, ref);
    if (!s.step()) return std::nullopt;
    JobRecord r = read_job(s);
    s.run();
    return r;
  }

  std::vector<JobRecord> dispatched() override {
    auto db = pool_.acquire();
    auto s = db->prepare(std::string("SELECT ") + kJobColumns +
                         " FROM jobs WHERE dispatch_ref IS NOT NULL ORDER BY seq");
    std::vector<JobRecord> out;
    while (s.step()) out.push_back(read_job(s));
    return out;
  }

  bool set_dispatch(const std::string& id, const std::string& status, const std::string& ref,
                    const std::string& message) override {
    auto db = pool_.acquire();
    db->prepare("UPDATE jobs SET dispatch_ref = ?, message = ?, updated = " GEARSPH_NOW
                " WHERE id = ? AND status = ? AND dispatch_ref IS NOT NULL")
        .bind(1, ref)
        .bind(2, message)
        .bind(3, id)
        .bind(4, status)
        .run();
    return db->changes() > 0;
  }

  bool release_dispatch(const std::string& id, const std::string& message) override {
    auto db = pool_.acquire();
    db->prepare("UPDATE jobs SET dispatch_ref = NULL, message = ?, updated = " GEARSPH_NOW
                " WHERE id = ? AND status = 'accepted'")
        .bind(1, message)
        .bind(2, id)
        .run();
    return db->changes() > 0;
  }

  bool start_dispatched(const std::string& id, const std::string& worker,
                        const std::string& message) override {
    auto db = pool_.acquire();
    db->prepare(
          "UPDATE jobs SET status = 'running', attempts = attempts + 1, worker = ?, "
          "message = ?, started = " GEARSPH_NOW ", updated = " GEARSPH_NOW
          ", finished = NULL, step = 0, simulated_s = 0, wall_s = 0, eta_s = 0, "
          "progress = 0 WHERE id = ? AND status = 'accepted' AND dispatch_ref IS NOT NULL")
        .bind(1, worker)
        .bind(2, message)
        .bind(3, id)
        .run();
    return db->changes() > 0;
  }

  void forget_dispatch(const std::string& id) override {
    auto db = pool_.acquire();
    db->prepare(
          "UPDATE jobs SET dispatch_ref = NULL WHERE id = ? AND status IN "
          "('successful', 'failed', 'dismissed')")
        .bind(1, id)
        .run();
  }

  std::vector<JobRecord> active_or_changed_within(double seconds) override {
    auto db = pool_.acquire();
    auto s = db->prepare(std::string("SELECT ") + kJobColumns +
                         " FROM jobs WHERE status IN ('accepted', 'running') OR updated >= "
                         "strftime('%Y-%m-%dT%H:%M:%fZ', 'now', ?) ORDER BY seq");
    char modifier[64];
    std::snprintf(modifier, sizeof modifier, "-%.3f seconds", std::max(0.0, seconds));
    s.bind(1, std::string_view(modifier));
    std::vector<JobRecord> out;
    while (s.step()) out.push_back(read_job(s));
    return out;
  }

 private:
  void migrate() {
    auto db = pool_.acquire();
    db->exec("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)");
    sqlite::Transaction tx(*db);
    std::int64_t version = 0;
    {
      auto s = db->prepare("SELECT version FROM schema_version");
      if (s.step()) {
        version = s.int64(0);
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
      db->prepare("UPDATE schema_version SET version = ?")
          .bind(1, static_cast<std::int64_t>(v + 1))
          .run();
    }
    tx.commit();
  }

  static std::optional<SubmitResult> check_key(sqlite::Connection& db,
                                               const std::optional<Idempotency>& idem) {
    if (!idem) return std::nullopt;
    auto s =
        db.prepare("SELECT request, target_id FROM idempotency_keys WHERE scope = ? AND key = ?");
    s.bind(1, idem->scope).bind(2, idem->key);
    if (!s.step()) return std::nullopt;
    const bool same = s.text(0) == idem->request;
    return SubmitResult{same ? SubmitResult::Kind::existing : SubmitResult::Kind::conflict,
                        s.text(1)};
  }

  static void remember_key(sqlite::Connection& db, const std::optional<Idempotency>& idem,
                           const std::string& target) {
    if (!idem) return;
    db.prepare(
          "INSERT INTO idempotency_keys (scope, key, request, target_id, created) VALUES "
          "(?, ?, ?, ?, " GEARSPH_NOW ")")
        .bind(1, idem->scope)
        .bind(2, idem->key)
        .bind(3, idem->request)
        .bind(4, target)
        .run();
  }

  static void insert_job(sqlite::Connection& db, const NewJob& j) {
    auto s = db.prepare(
        "INSERT INTO jobs (id, status, name, job_json, study_id, study_index, parameters_json, "
        "particles, steps, end_s, message, created, updated) VALUES (?, 'accepted', ?, ?, ?, ?, ?, "
        "?, ?, ?, 'queued', " GEARSPH_NOW ", " GEARSPH_NOW ")");
    s.bind(1, j.id).bind(2, j.name).bind(3, j.job_json);
    if (j.study_id.empty()) {
      s.bind_null(4);
    } else {
      s.bind(4, j.study_id);
    }
    s.bind(5, j.study_index).bind(6, j.parameters_json).bind(7, j.particles).bind(8, j.steps);
    s.bind(9, j.end_s);
    s.run();
  }

  sqlite::Pool pool_;
};

#undef GEARSPH_NOW
#undef GEARSPH_EPOCH

}  // namespace

std::unique_ptr<JobStore> open_sqlite_job_store(const std::filesystem::path& file) {
  return std::make_unique<SqliteJobStore>(file);
}

bool is_postgres_uri(std::string_view s) {
  return s.rfind("postgresql://", 0) == 0 || s.rfind("postgres://", 0) == 0;
}

std::unique_ptr<JobStore> open_job_store(const std::string& location) {
  if (is_postgres_uri(location)) return open_postgres_job_store(location);
  const std::string_view prefix = "sqlite:";
  if (location.rfind(prefix, 0) == 0) {
    return open_sqlite_job_store(location.substr(prefix.size()));
  }
  return open_sqlite_job_store(location);
}

}  // namespace gearsph::server
