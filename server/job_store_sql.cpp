// The job store's life cycle (job_store.hpp) once, in SQL that SQLite and
// PostgreSQL both speak; what differs between them (clocks, row locks,
// migrations) comes from the engine's sql::Dialect. Every state change is
// one statement or one transaction, and each statement names the status it
// moves a job from, so two processes never both move the same job.
#include <algorithm>
#include <cstdio>
#include <random>
#include <set>
#include <stdexcept>
#include <string>

#include "server/job_store.hpp"
#include "server/sql.hpp"

namespace gearsph::server {

std::string_view to_string(JobStatus s) {
  switch (s) {
    case JobStatus::accepted:
      return "accepted";
    case JobStatus::running:
      return "running";
    case JobStatus::successful:
      return "successful";
    case JobStatus::failed:
      return "failed";
    case JobStatus::dismissed:
      return "dismissed";
  }
  return "accepted";
}

std::optional<JobStatus> parse_job_status(std::string_view s) {
  for (JobStatus status : kJobStatuses) {
    if (to_string(status) == s) return status;
  }
  return std::nullopt;
}

bool is_job_status(std::string_view s) {
  return parse_job_status(s).has_value();
}

bool is_terminal_status(JobStatus s) {
  return s == JobStatus::successful || s == JobStatus::failed || s == JobStatus::dismissed;
}

namespace {

sql::Value text(JobStatus s) {
  return std::string(to_string(s));
}

const char* const kJobColumns =
    "id, status, name, job_json, study_id, study_index, parameters_json, particles, steps, "
    "end_s, step, simulated_s, wall_s, eta_s, progress, attempts, message, created, started, "
    "finished, updated, worker, dispatch_ref, claim, stage, fe_check";
const std::string kSelectJob = std::string("SELECT ") + kJobColumns + " FROM jobs";

JobRecord read_job(const sql::Row& r) {
  JobRecord j;
  j.id = r.text(0);
  const auto status = parse_job_status(r.text(1));
  if (!status) throw std::runtime_error("job " + j.id + " has an unknown status " + r.text(1));
  j.status = *status;
  j.name = r.text(2);
  j.job_json = r.text(3);
  j.study_id = r.text(4);
  j.study_index = r.int64(5);
  j.parameters_json = r.text(6);
  j.particles = r.int64(7);
  j.steps = r.int64(8);
  j.end_s = r.real(9);
  j.step = r.int64(10);
  j.simulated_s = r.real(11);
  j.wall_s = r.real(12);
  j.eta_s = r.real(13);
  j.progress = static_cast<int>(r.int64(14));
  j.attempts = static_cast<int>(r.int64(15));
  j.message = r.text(16);
  j.created = r.text(17);
  j.started = r.text(18);
  j.finished = r.text(19);
  j.updated = r.text(20);
  j.worker = r.text(21);
  j.dispatch_ref = r.text(22);
  j.claim = r.text(23);
  j.stage = r.text(24);
  j.fe_check_json = r.text(25);
  return j;
}

std::vector<JobRecord> read_jobs(const sql::Rows& rows) {
  std::vector<JobRecord> out;
  for (const sql::Row& r : rows) out.push_back(read_job(r));
  return out;
}

std::vector<std::string> ids_of(const sql::Rows& rows) {
  std::vector<std::string> out;
  for (const sql::Row& r : rows) out.push_back(r.text(0));
  return out;
}

// "?, ?, ?" for n parameters.
std::string placeholders(std::size_t n) {
  std::string s;
  for (std::size_t i = 0; i < n; ++i) s += i ? ", ?" : "?";
  return s;
}

// A job its claim still holds: running, or queued again after its lease
// ran out while nobody has claimed it since (a claim sets a new token).
const char* const kStillClaimed =
    "(status = 'running' OR (status = 'accepted' AND dispatch_ref IS NULL))";

// The condition under which a job may be moved: by the holder of `claim`
// while the claim is still its own; without a token, while it runs.
std::string held_by(const std::string& claim, sql::Values& params) {
  if (claim.empty()) return " AND status = 'running'";
  params.push_back(claim);
  return std::string(" AND claim = ? AND ") + kStillClaimed;
}

// Progress columns back to the start, for a run that starts (again).
const char* const kFromTheStart =
    "step = 0, simulated_s = 0, wall_s = 0, eta_s = 0, progress = 0, stage = NULL, fe_check = NULL";

// An empty text as SQL NULL.
sql::Value or_null(const std::string& s) {
  if (s.empty()) return std::monostate{};
  return s;
}

// "1 attempt", "2 attempts", said by SQL.
const char* const kAttemptsWord =
    "attempts || CASE WHEN attempts = 1 THEN ' attempt' ELSE ' attempts' END";

class SqlJobStore : public JobStore {
 public:
  explicit SqlJobStore(std::unique_ptr<sql::Database> db)
      : db_(std::move(db)), d_(db_->dialect()), now_(d_.now) {
    migrate();
  }

  using JobStore::submit;
  using JobStore::submit_study;

  SubmitResult submit(const NewJob& job, const std::optional<Idempotency>& idem,
                      const QueueQuota& quota) override {
    auto db = db_->connect();
    sql::Transaction tx(*db);
    lock_for_quota(*db, quota);
    if (auto seen = claim_key(*db, idem, job.id)) return *seen;
    if (auto over = over_quota(*db, quota, 1)) return *over;
    insert_job(*db, job);
    tx.commit();
    return {SubmitResult::Kind::created, job.id};
  }

  SubmitResult submit_study(const NewStudy& study, const std::vector<NewJob>& jobs,
                            const std::optional<Idempotency>& idem,
                            const QueueQuota& quota) override {
    auto db = db_->connect();
    sql::Transaction tx(*db);
    lock_for_quota(*db, quota);
    if (auto seen = claim_key(*db, idem, study.id)) return *seen;
    if (auto over = over_quota(*db, quota, static_cast<std::int64_t>(jobs.size()))) return *over;
    db->execute("INSERT INTO studies (id, name, spec_json, created) VALUES (?, ?, ?, " + now_ + ")",
                {study.id, study.name, study.spec_json});
    for (const NewJob& j : jobs) insert_job(*db, j);
    tx.commit();
    return {SubmitResult::Kind::created, study.id};
  }

  std::optional<JobRecord> job(const std::string& id) override {
    const auto rows = db_->connect()->query(kSelectJob + " WHERE id = ?", {id});
    if (rows.empty()) return std::nullopt;
    return read_job(rows.front());
  }

  JobPage jobs(const JobQuery& q) override {
    std::string where = " WHERE 1 = 1";
    sql::Values params;
    if (!q.statuses.empty()) {
      where += " AND status IN (" + placeholders(q.statuses.size()) + ")";
      for (JobStatus s : q.statuses) params.push_back(text(s));
    }
    if (!q.study_id.empty()) {
      where += " AND study_id = ?";
      params.push_back(q.study_id);
    }
    if (!q.created_from.empty()) {
      where += " AND created >= ?";
      params.push_back(q.created_from);
    }
    if (!q.created_to.empty()) {
      where += " AND created <= ?";
      params.push_back(q.created_to);
    }
    if (q.min_wall_s >= 0) {
      where += " AND wall_s >= ?";
      params.push_back(q.min_wall_s);
    }
    if (q.max_wall_s >= 0) {
      where += " AND wall_s <= ?";
      params.push_back(q.max_wall_s);
    }
    auto db = db_->connect();
    JobPage page;
    page.total = db->query("SELECT COUNT(*) FROM jobs" + where, params).front().int64(0);
    params.push_back(q.limit);
    params.push_back(q.offset);
    const std::string order = q.study_id.empty() ? " ORDER BY seq DESC" : " ORDER BY study_index";
    page.jobs = read_jobs(db->query(kSelectJob + where + order + " LIMIT ? OFFSET ?", params));
    return page;
  }

  std::optional<StudyRecord> study(const std::string& id) override {
    const auto rows = db_->connect()->query(
        "SELECT id, name, spec_json, created FROM studies WHERE id = ?", {id});
    if (rows.empty()) return std::nullopt;
    const sql::Row& r = rows.front();
    return StudyRecord{r.text(0), r.text(1), r.text(2), r.text(3)};
  }

  std::map<std::string, std::int64_t> count_by_status() override {
    std::map<std::string, std::int64_t> counts;
    for (JobStatus s : kJobStatuses) counts[std::string(to_string(s))] = 0;
    for (const sql::Row& r :
         db_->connect()->query("SELECT status, COUNT(*) FROM jobs GROUP BY status")) {
      counts[r.text(0)] = r.int64(1);
    }
    return counts;
  }

  std::int64_t queued_from(const std::string& client) override {
    return db_->connect()
        ->query("SELECT COUNT(*) FROM jobs WHERE status = 'accepted' AND client = ?", {client})
        .front()
        .int64(0);
  }

  std::int64_t open_session(const std::string& id_hash, double lifetime_s,
                            std::int64_t max_sessions) override {
    auto db = db_->connect();
    sql::Transaction tx(*db);
    db->execute("DELETE FROM sessions WHERE expires <= " + d_.lease_clock);
    const std::int64_t open = db->query("SELECT COUNT(*) FROM sessions").front().int64(0);
    std::int64_t evicted = 0;
    if (open >= max_sessions) {
      evicted = db->execute(
          "DELETE FROM sessions WHERE id_hash IN "
          "(SELECT id_hash FROM sessions ORDER BY expires LIMIT ?)",
          {open - max_sessions + 1});
    }
    db->execute("INSERT INTO sessions (id_hash, expires) VALUES (?, " + d_.lease_in + ")",
                {id_hash, lifetime_s});
    tx.commit();
    return evicted;
  }

  bool session_open(const std::string& id_hash) override {
    return !db_->connect()
                ->query("SELECT 1 FROM sessions WHERE id_hash = ? AND expires > " + d_.lease_clock,
                        {id_hash})
                .empty();
  }

  bool close_session(const std::string& id_hash) override {
    return db_->connect()->execute("DELETE FROM sessions WHERE id_hash = ?", {id_hash}) > 0;
  }

  std::int64_t open_sessions() override {
    return db_->connect()
        ->query("SELECT COUNT(*) FROM sessions WHERE expires > " + d_.lease_clock)
        .front()
        .int64(0);
  }

  std::optional<JobRecord> claim(const Holder& holder) override {
    // One statement: two workers can never claim the same job.
    const auto rows = db_->connect()->query(
        "UPDATE jobs SET status = 'running', attempts = attempts + 1, "
        "message = 'running' || CASE WHEN attempts > 0 THEN ' (attempt ' || (attempts + 1) || "
        "')' ELSE '' END, started = " +
            now_ + ", updated = " + now_ + ", finished = NULL, " + kFromTheStart +
            ", worker = ?, claim = ?, lease_until = CASE WHEN " + d_.seconds_param + " > 0 THEN " +
            d_.lease_in +
            " ELSE NULL END WHERE seq = (SELECT seq FROM jobs WHERE status = 'accepted' AND "
            "dispatch_ref IS NULL ORDER BY seq LIMIT 1" +
            d_.skip_locked + ") RETURNING " + kJobColumns,
        {holder.worker, new_claim_token(), holder.lease_s, holder.lease_s});
    if (rows.empty()) return std::nullopt;
    return read_job(rows.front());
  }

  std::vector<std::string> renew(const Holder& holder, const std::vector<HeldJob>& held) override {
    if (held.empty()) return {};
    // A job queued again after its lease ran out, and not claimed since,
    // runs on under the same claim (its holder was cut off, not gone).
    sql::Values params{holder.lease_s};
    std::string which;
    for (const HeldJob& h : held) {
      which += which.empty() ? "(id = ? AND claim = ?)" : " OR (id = ? AND claim = ?)";
      params.push_back(h.id);
      params.push_back(h.claim);
    }
    const auto kept_rows = db_->connect()->query(
        "UPDATE jobs SET lease_until = " + d_.lease_in +
            ", updated = CASE WHEN status = 'accepted' THEN " + now_ +
            " ELSE updated END, message = CASE WHEN status = 'accepted' THEN 'running (its worker "
            "is back after its lease ran out; nobody had claimed it since)' ELSE message END, "
            "started = "
            "COALESCE(started, " +
            now_ + "), status = 'running' WHERE " + kStillClaimed + " AND (" + which +
            ") RETURNING id",
        params);
    const std::vector<std::string> kept_ids = ids_of(kept_rows);
    const std::set<std::string> kept(kept_ids.begin(), kept_ids.end());
    std::vector<std::string> lost;
    for (const HeldJob& h : held) {
      if (!kept.count(h.id)) lost.push_back(h.id);
    }
    return lost;
  }

  Recovery reclaim_expired(int max_attempts) override {
    const std::string expired = " WHERE status = 'running' AND lease_until < " + d_.lease_clock;
    const std::string whose =
        "'its worker ' || worker || ' stopped renewing its lease during attempt ' || attempts";
    Recovery out;
    auto db = db_->connect();
    sql::Transaction tx(*db);
    out.failed = ids_of(db->query(
        "UPDATE jobs SET status = 'failed', eta_s = 0, lease_until = NULL, claim = NULL, "
        "message = " +
            whose + " || '; not started again after ' || " + kAttemptsWord + ", finished = " +
            now_ + ", updated = " + now_ + expired + " AND attempts >= ? RETURNING id",
        {std::int64_t{max_attempts}}));
    out.requeued = ids_of(db->query(
        "UPDATE jobs SET status = 'accepted', lease_until = NULL, message = 're-queued: ' || " +
        whose + " || '; the job starts again from the beginning', started = NULL, " +
        kFromTheStart + ", updated = " + now_ + expired + " RETURNING id"));
    tx.commit();
    return out;
  }

  std::vector<std::string> save_progress(const std::vector<ProgressUpdate>& batch) override {
    std::vector<std::string> gone;
    if (batch.empty()) return gone;
    auto db = db_->connect();
    sql::Transaction tx(*db);
    for (const ProgressUpdate& u : batch) {
      const auto changed = db->execute(
          "UPDATE jobs SET step = ?, simulated_s = ?, wall_s = ?, eta_s = ?, progress = ?, "
          "stage = ?, fe_check = ?, updated = " +
              now_ + " WHERE id = ? AND status = 'running'",
          {u.step, u.simulated_s, u.wall_s, u.eta_s, std::int64_t{u.progress}, or_null(u.stage),
           or_null(u.fe_check_json), u.id});
      if (changed == 0) gone.push_back(u.id);
    }
    tx.commit();
    return gone;
  }

  bool finish(const std::string& id, JobStatus status, const std::string& message,
              const ProgressUpdate& last, const std::string& claim) override {
    sql::Values params{text(status),
                       message,
                       last.step,
                       last.simulated_s,
                       last.wall_s,
                       std::int64_t{last.progress},
                       or_null(last.fe_check_json),
                       id};
    const std::string held = held_by(claim, params);
    return db_->connect()->execute(
               "UPDATE jobs SET status = ?, message = ?, step = ?, simulated_s = ?, wall_s = ?, "
               "eta_s = 0, progress = ?, stage = NULL, fe_check = ?, lease_until = NULL, "
               "dispatch_ref = NULL, started = "
               "COALESCE(started, " +
                   now_ + "), finished = " + now_ + ", updated = " + now_ + " WHERE id = ?" + held,
               params) > 0;
  }

  bool close_dismissed(const std::string& id, const std::string& message,
                       const ProgressUpdate& last) override {
    return db_->connect()->execute(
               "UPDATE jobs SET message = ?, step = ?, simulated_s = ?, wall_s = ?, eta_s = 0, "
               "progress = ?, stage = NULL, fe_check = ?, lease_until = NULL, finished = " +
                   now_ + ", updated = " + now_ + " WHERE id = ? AND status = 'dismissed'",
               {message, last.step, last.simulated_s, last.wall_s, std::int64_t{last.progress},
                or_null(last.fe_check_json), id}) > 0;
  }

  bool requeue(const std::string& id, const std::string& message,
               const std::string& claim) override {
    sql::Values params{message, id};
    std::string held = " AND status = 'running'";
    if (!claim.empty()) {
      held += " AND claim = ?";
      params.push_back(claim);
    }
    return db_->connect()->execute(
               "UPDATE jobs SET status = 'accepted', "
               "attempts = CASE WHEN attempts > 0 THEN attempts - 1 ELSE 0 END, message = ?, "
               "started = NULL, " +
                   std::string(kFromTheStart) +
                   ", lease_until = NULL, claim = NULL, updated = " + now_ + " WHERE id = ?" + held,
               params) > 0;
  }

  std::optional<JobRecord> dismiss(const std::string& id) override {
    auto db = db_->connect();
    sql::Transaction tx(*db);
    const auto rows = db->query(kSelectJob + " WHERE id = ?" + d_.lock_row, {id});
    if (rows.empty()) return std::nullopt;
    JobRecord before = read_job(rows.front());
    if (before.status != JobStatus::dismissed) {
      db->execute("UPDATE jobs SET status = 'dismissed', message = ?, eta_s = 0, finished = " +
                      now_ + ", updated = " + now_ + " WHERE id = ?",
                  {dismissal_message(before.status), id});
    }
    tx.commit();
    return before;
  }

  Recovery recover(int max_attempts) override {
    // The server's own pool: no lease, no scheduler.
    const std::string own =
        " WHERE status = 'running' AND lease_until IS NULL AND dispatch_ref IS NULL";
    Recovery out;
    auto db = db_->connect();
    sql::Transaction tx(*db);
    out.failed = ids_of(db->query(
        "UPDATE jobs SET status = 'failed', eta_s = 0, claim = NULL, message = 'interrupted ' "
        "|| attempts || "
        "CASE WHEN attempts = 1 THEN ' time' ELSE ' times' END || ' (the server stopped while "
        "it ran); not started again after ' || " +
            std::string(kAttemptsWord) + ", finished = " + now_ + ", updated = " + now_ + own +
            " AND attempts >= ? RETURNING id",
        {std::int64_t{max_attempts}}));
    out.requeued = ids_of(db->query(
        "UPDATE jobs SET status = 'accepted', message = 're-queued: the server stopped while "
        "attempt ' || attempts || ' ran; the job starts again from the beginning', "
        "started = NULL, claim = NULL, " +
        std::string(kFromTheStart) + ", updated = " + now_ + own + " RETURNING id"));
    tx.commit();
    return out;
  }

  std::optional<JobRecord> claim_for_dispatch(const std::string& ref) override {
    const auto rows = db_->connect()->query(
        "UPDATE jobs SET dispatch_ref = ?, updated = " + now_ +
            " WHERE seq = (SELECT seq FROM jobs WHERE status = 'accepted' AND dispatch_ref IS "
            "NULL ORDER BY seq LIMIT 1" +
            d_.skip_locked + ") RETURNING " + kJobColumns,
        {ref});
    if (rows.empty()) return std::nullopt;
    return read_job(rows.front());
  }

  std::vector<JobRecord> dispatched() override {
    return read_jobs(
        db_->connect()->query(kSelectJob + " WHERE dispatch_ref IS NOT NULL ORDER BY seq"));
  }

  bool set_dispatch(const std::string& id, JobStatus status, const std::string& expected,
                    const std::string& ref, const std::string& message, double min_age_s) override {
    return db_->connect()->execute(
               "UPDATE jobs SET dispatch_ref = ?, message = ?, updated = " + now_ +
                   " WHERE id = ? AND status = ? AND dispatch_ref = ? AND "
                   "updated <= " +
                   d_.time_ago,
               {ref, message, id, text(status), expected, min_age_s}) > 0;
  }

  bool release_dispatch(const std::string& id, const std::string& expected,
                        const std::string& message, double min_age_s) override {
    return db_->connect()->execute(
               "UPDATE jobs SET dispatch_ref = NULL, message = ?, updated = " + now_ +
                   " WHERE id = ? AND status = 'accepted' AND dispatch_ref = ? AND updated <= " +
                   d_.time_ago,
               {message, id, expected, min_age_s}) > 0;
  }

  bool start_dispatched(const std::string& id, const std::string& worker,
                        const std::string& message) override {
    return db_->connect()->execute(
               "UPDATE jobs SET status = 'running', attempts = attempts + 1, worker = ?, "
               "message = ?, started = " +
                   now_ + ", updated = " + now_ + ", finished = NULL, " + kFromTheStart +
                   " WHERE id = ? AND status = 'accepted' AND dispatch_ref IS NOT NULL",
               {worker, message, id}) > 0;
  }

  bool unstart_dispatched(const std::string& id, const std::string& ref,
                          const std::string& message) override {
    return db_->connect()->execute(
               "UPDATE jobs SET status = 'accepted', message = ?, started = NULL, " +
                   std::string(kFromTheStart) + ", updated = " + now_ +
                   " WHERE id = ? AND status = 'running' AND dispatch_ref = ?",
               {message, id, ref}) > 0;
  }

  void forget_dispatch(const std::string& id) override {
    db_->connect()->execute(
        "UPDATE jobs SET dispatch_ref = NULL WHERE id = ? AND status IN "
        "('successful', 'failed', 'dismissed')",
        {id});
  }

  void worker_seen(const std::string& worker, int running) override {
    db_->connect()->execute(
        "INSERT INTO workers (name, started, seen, running) VALUES (?, " + now_ + ", " + now_ +
            ", ?) ON CONFLICT (name) DO UPDATE SET seen = excluded.seen, running = "
            "excluded.running",
        {worker, std::int64_t{running}});
  }

  std::vector<WorkerSeen> workers_seen(double seconds) override {
    // Ages from the store's clock: the machines' clocks need not agree.
    std::vector<WorkerSeen> out;
    for (const sql::Row& r : db_->connect()->query(
             "SELECT name, " + seconds_since("seen") +
                 ", running FROM workers WHERE seen >= " + d_.time_ago + " ORDER BY name",
             {seconds})) {
      out.push_back({r.text(0), r.real(1), static_cast<int>(r.int64(2))});
    }
    return out;
  }

  Durations durations(const std::vector<double>& bounds) override {
    Durations d;
    d.bounds = bounds;
    std::string select = "SELECT COUNT(*), COALESCE(SUM(wall_s), 0)";
    sql::Values params;
    for (double b : bounds) {
      select += ", COALESCE(SUM(CASE WHEN wall_s <= ? THEN 1 ELSE 0 END), 0)";
      params.push_back(b);
    }
    const auto rows = db_->connect()->query(
        select + " FROM jobs WHERE status IN ('successful', 'failed')", params);
    const sql::Row& r = rows.front();
    d.count = r.int64(0);
    d.sum_s = r.real(1);
    for (std::size_t i = 0; i < bounds.size(); ++i) d.at_most.push_back(r.int64(2 + i));
    return d;
  }

  std::vector<std::string> prune(double seconds) override {
    auto db = db_->connect();
    sql::Transaction tx(*db);
    const auto ids = ids_of(
        db->query("DELETE FROM jobs WHERE status IN ('successful', 'failed', 'dismissed') AND "
                  "COALESCE(finished, updated) < " +
                      d_.time_ago + " RETURNING id",
                  {seconds}));
    db->execute("DELETE FROM studies WHERE created < " + d_.time_ago +
                    " AND NOT EXISTS (SELECT 1 FROM jobs WHERE jobs.study_id = studies.id)",
                {seconds});
    db->execute("DELETE FROM idempotency_keys WHERE created < " + d_.time_ago, {seconds});
    db->execute("DELETE FROM workers WHERE seen < " + d_.time_ago, {seconds});
    tx.commit();
    return ids;
  }

  bool notifies() const override { return db_->notifies(); }
  bool wait_for_change(std::chrono::milliseconds timeout) override {
    return db_->wait_for_change(timeout);
  }

  std::vector<JobRecord> changed_within(double seconds) override {
    // Through the index on `updated`; '' for the job document, which no
    // event needs (a queued study of thousands is not read every time).
    std::string columns = kJobColumns;
    columns.replace(columns.find("job_json"), 8, "'' AS job_json");
    return read_jobs(db_->connect()->query(
        "SELECT " + columns + " FROM jobs WHERE updated >= " + d_.time_ago + " ORDER BY seq",
        {std::max(0.0, seconds)}));
  }

  std::vector<JobRecord> active_or_changed_within(double seconds) override {
    return read_jobs(db_->connect()->query(
        kSelectJob + " WHERE status IN ('accepted', 'running') OR updated >= " + d_.time_ago +
            " ORDER BY seq",
        {std::max(0.0, seconds)}));
  }

 private:
  static std::string dismissal_message(JobStatus before) {
    switch (before) {
      case JobStatus::accepted:
        return "dismissed before it started";
      case JobStatus::running:
        return "dismissed while running; the run stops at its next check";
      case JobStatus::successful:
        return "dismissed after it had completed; its files were deleted";
      default:
        return "dismissed after it had failed; its files were deleted";
    }
  }

  void migrate() {
    auto db = db_->connect();
    if (d_.migration_lock.empty()) {  // outside the transaction, as before BEGIN IMMEDIATE
      db->script("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)");
    }
    sql::Transaction tx(*db);
    if (!d_.migration_lock.empty()) {
      db->query(d_.migration_lock);
      db->script("CREATE TABLE IF NOT EXISTS schema_version (version INTEGER NOT NULL)");
    }
    std::int64_t version = 0;
    const auto rows = db->query("SELECT version FROM schema_version");
    if (!rows.empty()) {
      version = rows.front().int64(0);
    } else {
      db->execute("INSERT INTO schema_version (version) VALUES (0)");
    }
    const auto known = static_cast<std::int64_t>(d_.migrations.size());
    if (version > known) {
      throw std::runtime_error("the job database has schema version " + std::to_string(version) +
                               ", newer than this gearsph (" + std::to_string(known) +
                               "); upgrade gearsph");
    }
    for (auto v = version; v < known; ++v) {
      db->script(d_.migrations[static_cast<std::size_t>(v)]);
      db->execute("UPDATE schema_version SET version = ?", {v + 1});
    }
    tx.commit();
  }

  // Records the key for `target`, or answers with what it was used for
  // before. Inside the submission's transaction: two nodes given the same
  // key at once agree on one job (PostgreSQL waits for the other insert).
  // Submissions under a quota one at a time: SQLite's BEGIN IMMEDIATE does
  // it already; PostgreSQL's READ COMMITTED would let two count the same
  // queue and both insert (Dialect::submit_lock).
  void lock_for_quota(sql::Connection& db, const QueueQuota& q) {
    if (d_.submit_lock.empty()) return;
    if (q.max_queued <= 0 && (q.max_queued_per_client <= 0 || q.client.empty())) return;
    db.query(d_.submit_lock);
  }

  // Counted in the transaction that inserts: the queue as it is now.
  std::optional<SubmitResult> over_quota(sql::Connection& db, const QueueQuota& q,
                                         std::int64_t adding) {
    if (q.max_queued > 0) {
      const std::int64_t queued =
          db.query("SELECT COUNT(*) FROM jobs WHERE status = 'accepted'").front().int64(0);
      if (queued + adding > q.max_queued) {
        return SubmitResult{SubmitResult::Kind::queue_full, "", queued};
      }
    }
    if (q.max_queued_per_client > 0 && !q.client.empty()) {
      const std::int64_t mine =
          db.query("SELECT COUNT(*) FROM jobs WHERE status = 'accepted' AND client = ?", {q.client})
              .front()
              .int64(0);
      if (mine + adding > q.max_queued_per_client) {
        return SubmitResult{SubmitResult::Kind::client_queue_full, "", mine};
      }
    }
    return std::nullopt;
  }

  std::optional<SubmitResult> claim_key(sql::Connection& db, const std::optional<Idempotency>& idem,
                                        const std::string& target) {
    if (!idem) return std::nullopt;
    const auto inserted = db.execute(
        "INSERT INTO idempotency_keys (scope, key, request, target_id, created) VALUES "
        "(?, ?, ?, ?, " +
            now_ + ") ON CONFLICT (scope, key) DO NOTHING",
        {idem->scope, idem->key, idem->request, target});
    if (inserted > 0) return std::nullopt;
    const auto rows =
        db.query("SELECT request, target_id FROM idempotency_keys WHERE scope = ? AND key = ?",
                 {idem->scope, idem->key});
    const bool same = rows.front().text(0) == idem->request;
    return SubmitResult{same ? SubmitResult::Kind::existing : SubmitResult::Kind::conflict,
                        rows.front().text(1)};
  }

  void insert_job(sql::Connection& db, const NewJob& j) {
    db.execute(
        "INSERT INTO jobs (id, status, name, job_json, study_id, study_index, parameters_json, "
        "particles, steps, end_s, client, message, created, updated) VALUES (?, 'accepted', ?, "
        "?, ?, ?, ?, ?, ?, ?, ?, 'queued', " +
            now_ + ", " + now_ + ")",
        {j.id, j.name, j.job_json, j.study_id.empty() ? sql::Value() : sql::Value(j.study_id),
         j.study_index, j.parameters_json, j.particles, j.steps, j.end_s, or_null(j.client)});
  }

  std::string seconds_since(const std::string& column) const {
    std::string s = d_.seconds_since;
    return s.replace(s.find("{}"), 2, column);
  }

  std::unique_ptr<sql::Database> db_;
  const sql::Dialect& d_;
  const std::string now_;
};

}  // namespace

std::unique_ptr<JobStore> open_sql_job_store(std::unique_ptr<sql::Database> db) {
  return std::make_unique<SqlJobStore>(std::move(db));
}

std::string new_claim_token() {
  static thread_local std::mt19937_64 bits = [] {
    std::random_device seed;
    std::seed_seq seq{seed(), seed(), seed(), seed(), seed(), seed(), seed(), seed()};
    return std::mt19937_64(seq);
  }();
  char text[33];
  std::snprintf(text, sizeof text, "%016llx%016llx", static_cast<unsigned long long>(bits()),
                static_cast<unsigned long long>(bits()));
  return text;
}

}  // namespace gearsph::server
