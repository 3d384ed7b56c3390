// The job store's SQL seam on SQLite: one file, WAL (readers never wait for
// the writer), busy timeout (writers wait for each other), BEGIN IMMEDIATE
// (a transaction takes the write lock up front), and CHECK constraints so
// no row can hold a state the life cycle does not know.
#include <sqlite3.h>

#include <filesystem>

#include "server/job_store.hpp"
#include "server/sql.hpp"
#include "server/sqlite.hpp"

namespace gearsph::server {
namespace {

// Migration i brings the schema from version i to i + 1. Append, never edit.
const char* const kMigration1 = R"sql(
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
)sql";

// 2: claims with leases (worker processes), outside schedulers (Slurm).
const char* const kMigration2 = R"sql(
ALTER TABLE jobs ADD COLUMN worker TEXT;
ALTER TABLE jobs ADD COLUMN lease_until REAL;
ALTER TABLE jobs ADD COLUMN dispatch_ref TEXT;
CREATE INDEX jobs_by_dispatch ON jobs(dispatch_ref) WHERE dispatch_ref IS NOT NULL;
)sql";

// 3, 4 and 5: sql.hpp.

// 6: the dashboard's sessions, shared by every process of the store
// (sessions.hpp): the SHA-256 of each session id, never the id, and when
// it ends, on the lease clock (seconds since 1970).
const char* const kMigration6 = R"sql(
CREATE TABLE sessions (
  id_hash TEXT PRIMARY KEY,
  expires REAL NOT NULL
);
CREATE INDEX sessions_by_expiry ON sessions(expires);
)sql";

// Seconds since 1970 on SQLite's clock: leases are REAL.
#define GEARSPH_EPOCH "((julianday('now') - 2440587.5) * 86400.0)"

sql::Dialect sqlite_dialect() {
  return sql::Dialect{
      .now = "strftime('%Y-%m-%dT%H:%M:%fZ','now')",
      .seconds_param = "?",
      .lease_clock = GEARSPH_EPOCH,
      .lease_in = GEARSPH_EPOCH " + ?",
      .time_ago = "strftime('%Y-%m-%dT%H:%M:%fZ', 'now', printf('-%.3f seconds', ?))",
      .seconds_since = "((julianday('now') - julianday({})) * 86400.0)",
      .skip_locked = "",  // one writer at a time: the claim's UPDATE is atomic as it is
      .lock_row = "",     // BEGIN IMMEDIATE holds the write lock already
      .migration_lock = "",
      .submit_lock = "",  // BEGIN IMMEDIATE: one writer at a time
      .migrations = {kMigration1, kMigration2, sql::kClaimTokens, sql::kWorkerHeartbeats,
                     sql::kStages, kMigration6},
  };
}

#undef GEARSPH_EPOCH

class SqliteConnection : public sql::Connection {
 public:
  explicit SqliteConnection(sqlite::Pool::Lease lease) : db_(std::move(lease)) {}

  sql::Rows query(const std::string& text, const sql::Values& params) override {
    auto s = db_->prepare(text);
    bind_all(s, params);
    sql::Rows rows;
    while (s.step()) {
      std::vector<sql::Value> cells;
      for (int c = 0; c < s.columns(); ++c) cells.push_back(cell(s, c));
      rows.emplace_back(std::move(cells));
    }
    return rows;
  }

  std::int64_t execute(const std::string& text, const sql::Values& params) override {
    auto s = db_->prepare(text);
    bind_all(s, params);
    s.run();
    return db_->changes();
  }

  void script(const std::string& text) override { db_->exec(text); }
  // BEGIN IMMEDIATE takes the write lock up front, so two writers never
  // deadlock upgrading read locks.
  void begin() override { db_->exec("BEGIN IMMEDIATE"); }
  void commit() override { db_->exec("COMMIT"); }
  void rollback() override { db_->exec("ROLLBACK"); }

 private:
  static void bind_all(sqlite::Statement& s, const sql::Values& params) {
    for (std::size_t i = 0; i < params.size(); ++i) {
      const int index = static_cast<int>(i) + 1;
      std::visit(
          [&](const auto& v) {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, std::monostate>) {
              s.bind_null(index);
            } else if constexpr (std::is_same_v<T, std::string>) {
              s.bind(index, std::string_view(v));
            } else {
              s.bind(index, v);
            }
          },
          params[i]);
    }
  }

  static sql::Value cell(const sqlite::Statement& s, int column) {
    switch (s.type(column)) {
      case SQLITE_NULL:
        return std::monostate{};
      case SQLITE_INTEGER:
        return s.int64(column);
      case SQLITE_FLOAT:
        return s.real(column);
      default:
        return s.text(column);
    }
  }

  sqlite::Pool::Lease db_;
};

class SqliteDatabase : public sql::Database {
 public:
  explicit SqliteDatabase(const std::filesystem::path& file)
      : pool_(file), dialect_(sqlite_dialect()) {}
  const sql::Dialect& dialect() const override { return dialect_; }
  std::unique_ptr<sql::Connection> connect() override {
    return std::make_unique<SqliteConnection>(pool_.acquire());
  }

 private:
  sqlite::Pool pool_;
  const sql::Dialect dialect_;
};

}  // namespace

std::unique_ptr<JobStore> open_sqlite_job_store(const std::filesystem::path& file) {
  return open_sql_job_store(std::make_unique<SqliteDatabase>(file));
}

}  // namespace gearsph::server
