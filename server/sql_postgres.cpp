// The job store's SQL seam on PostgreSQL: one database shared by any number
// of API nodes and worker processes. Claims pick their row with
// FOR UPDATE SKIP LOCKED, so workers never wait for each other and never get
// the same job; leases are on the database's clock; migrations run under an
// advisory lock, so processes starting together migrate once.
#include <string>

#include "server/job_store.hpp"

#ifdef GEARSPH_WITH_POSTGRESQL
#include "server/postgres.hpp"
#include "server/sql.hpp"
#endif

namespace gearsph::server {

#ifndef GEARSPH_WITH_POSTGRESQL

std::unique_ptr<JobStore> open_postgres_job_store(const std::string&) {
  throw std::runtime_error(
      "this gearsph was built without PostgreSQL (install libpq-dev and build again)");
}

#else

namespace {

// Migration i brings the schema from version i to i + 1. Append, never edit.
const char* const kMigration1 = R"sql(
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
)sql";

// 2, 3 and 5: sql.hpp.

// 4: every inserted or changed job is announced on the channel gearsph_jobs
// (LISTEN/NOTIFY): API nodes wait for it instead of reading the table.
const char* const kMigration4 = R"sql(
CREATE FUNCTION gearsph_jobs_changed() RETURNS trigger AS $$
BEGIN
  PERFORM pg_notify('gearsph_jobs', NEW.id);
  RETURN NULL;
END
$$ LANGUAGE plpgsql;
CREATE TRIGGER gearsph_jobs_changed AFTER INSERT OR UPDATE ON jobs
  FOR EACH ROW EXECUTE FUNCTION gearsph_jobs_changed();
)sql";

// 6: the dashboard's sessions, shared by every API node (sessions.hpp): the
// SHA-256 of each session id, never the id, and when it ends.
const char* const kMigration6 = R"sql(
CREATE TABLE sessions (
  id_hash TEXT PRIMARY KEY,
  expires TIMESTAMPTZ NOT NULL
);
CREATE INDEX sessions_by_expiry ON sessions(expires);
)sql";

// ISO 8601 UTC with milliseconds, as SQLite's strftime writes them.
#define GEARSPH_ISO(t) "to_char((" t ") AT TIME ZONE 'UTC', 'YYYY-MM-DD\"T\"HH24:MI:SS.MS\"Z\"')"

sql::Dialect postgres_dialect() {
  return sql::Dialect{
      .now = GEARSPH_ISO("clock_timestamp()"),
      .seconds_param = "?::float8",
      .lease_clock = "clock_timestamp()",
      .lease_in = "clock_timestamp() + ?::float8 * interval '1 second'",
      .time_ago = GEARSPH_ISO("clock_timestamp() - ?::float8 * interval '1 second'"),
      .seconds_since = "EXTRACT(EPOCH FROM clock_timestamp() - ({})::timestamptz)::float8",
      // A job another worker is claiming right now is passed over, not waited for.
      .skip_locked = " FOR UPDATE SKIP LOCKED",
      .lock_row = " FOR UPDATE",
      .migration_lock = "SELECT pg_advisory_xact_lock(7146301)",  // any fixed number
      // Only submissions wait for each other; workers' updates of the jobs do not.
      .submit_lock = "SELECT pg_advisory_xact_lock(7146302)",
      .migrations = {kMigration1, sql::kClaimTokens, sql::kWorkerHeartbeats, kMigration4,
                     sql::kStages, kMigration6},
  };
}

#undef GEARSPH_ISO

// "... ? ... ?" -> "... $1 ... $2", leaving quoted text alone.
std::string numbered_parameters(const std::string& sql) {
  std::string out;
  int n = 0;
  char quote = 0;
  for (char c : sql) {
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '\'' || c == '"') {
      quote = c;
    } else if (c == '?') {
      out += '$' + std::to_string(++n);
      continue;
    }
    out += c;
  }
  return out;
}

postgres::Params params_of(const sql::Values& values) {
  postgres::Params out;
  for (const sql::Value& v : values) {
    std::visit(
        [&](const auto& x) {
          using T = std::decay_t<decltype(x)>;
          if constexpr (std::is_same_v<T, std::monostate>) {
            out.push_back(postgres::Param());
          } else {
            out.push_back(postgres::param(x));
          }
        },
        v);
  }
  return out;
}

// A connection that failed or was lost (SQLSTATE class 08, or none: libpq
// could not reach the server) and a server shutting down or starting
// (57P01-57P03): the store is away, not the request wrong.
bool unreachable(const postgres::Error& e) {
  return e.sqlstate.empty() || e.sqlstate.rfind("08", 0) == 0 || e.sqlstate.rfind("57P0", 0) == 0;
}

template <class F>
auto guarded(F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const postgres::Error& e) {
    if (unreachable(e)) throw StoreUnavailable(e.what());
    throw;
  }
}

class PostgresConnection : public sql::Connection {
 public:
  explicit PostgresConnection(postgres::Pool::Lease lease) : db_(std::move(lease)) {}

  sql::Rows query(const std::string& text, const sql::Values& params) override {
    const postgres::Result r =
        guarded([&] { return db_->exec(numbered_parameters(text), params_of(params)); });
    sql::Rows rows;
    for (int i = 0; i < r.rows(); ++i) {
      std::vector<sql::Value> cells;
      for (int c = 0; c < r.columns(); ++c) {
        if (r.is_null(i, c)) {
          cells.emplace_back(std::monostate{});
        } else {
          cells.emplace_back(r.text(i, c));
        }
      }
      rows.emplace_back(std::move(cells));
    }
    return rows;
  }

  std::int64_t execute(const std::string& text, const sql::Values& params) override {
    return guarded([&] { return db_->exec(numbered_parameters(text), params_of(params)); })
        .affected();
  }

  void script(const std::string& text) override {
    guarded([&] { db_->exec(text); });
  }
  void begin() override {
    guarded([&] { db_->exec("BEGIN"); });
  }
  void commit() override {
    guarded([&] { db_->exec("COMMIT"); });
  }
  void rollback() override {
    if (db_->ok()) db_->exec("ROLLBACK");  // else the server rolled back already
  }

 private:
  postgres::Pool::Lease db_;
};

class PostgresDatabase : public sql::Database {
 public:
  explicit PostgresDatabase(const std::string& uri)
      : uri_(uri), pool_(uri), dialect_(postgres_dialect()) {}
  const sql::Dialect& dialect() const override { return dialect_; }
  std::unique_ptr<sql::Connection> connect() override {
    return std::make_unique<PostgresConnection>(guarded([&] { return pool_.acquire(); }));
  }

  bool notifies() const override { return true; }

  // On a connection of its own that LISTENs, made again after a failure.
  bool wait_for_change(std::chrono::milliseconds timeout) override {
    return guarded([&] {
      try {
        if (!listener_ || !listener_->ok()) {
          listener_.reset();
          auto c = std::make_unique<postgres::Connection>(uri_);
          c->exec("LISTEN gearsph_jobs");
          listener_ = std::move(c);
          return true;  // (re)connected: something may have changed meanwhile
        }
        return listener_->wait_for_notification(static_cast<int>(timeout.count()));
      } catch (...) {
        listener_.reset();
        throw;
      }
    });
  }

 private:
  std::string uri_;
  std::unique_ptr<postgres::Connection> listener_;  // the watcher's thread only
  postgres::Pool pool_;
  const sql::Dialect dialect_;
};

}  // namespace

std::unique_ptr<JobStore> open_postgres_job_store(const std::string& uri) {
  return open_sql_job_store(std::make_unique<PostgresDatabase>(uri));
}

#endif

}  // namespace gearsph::server
