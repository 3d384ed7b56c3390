#pragma once
// The seam between the job store (job_store_sql.cpp) and an SQL engine:
// statements with `?` parameters, their rows, transactions, and the few
// pieces of SQL that differ between engines (the Dialect). SQLite
// (sql_sqlite.cpp) and PostgreSQL (sql_postgres.cpp) each implement it over
// their thin RAII layer (sqlite.hpp, postgres.hpp).
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace gearsph::server::sql {

// One SQL value: NULL, an integer, a real or a text.
using Value = std::variant<std::monostate, std::int64_t, double, std::string>;
using Values = std::vector<Value>;

class Row {
 public:
  explicit Row(std::vector<Value> cells) : cells_(std::move(cells)) {}
  // Columns are numbered from 0; NULL reads as "" or 0.
  std::string text(std::size_t column) const;
  std::int64_t int64(std::size_t column) const;
  double real(std::size_t column) const;

 private:
  std::vector<Value> cells_;
};
using Rows = std::vector<Row>;

// A connection, held for one store operation.
class Connection {
 public:
  virtual ~Connection() = default;
  // One statement; its rows (of a SELECT or a RETURNING clause).
  virtual Rows query(const std::string& sql, const Values& params = {}) = 0;
  // One statement; the number of rows it inserted, updated or deleted.
  virtual std::int64_t execute(const std::string& sql, const Values& params = {}) = 0;
  // Statements without parameters, separated by semicolons (migrations).
  virtual void script(const std::string& sql) = 0;
  // A transaction that takes the write lock up front where the engine has one.
  virtual void begin() = 0;
  virtual void commit() = 0;
  virtual void rollback() = 0;
};

// Rolls back unless committed.
class Transaction {
 public:
  explicit Transaction(Connection& db) : db_(db) { db_.begin(); }
  ~Transaction();
  Transaction(const Transaction&) = delete;
  Transaction& operator=(const Transaction&) = delete;
  void commit() {
    db_.commit();
    done_ = true;
  }

 private:
  Connection& db_;
  bool done_ = false;
};

// Migrations both engines run as they are:
// a token per claim, which fences every later move of the job (worker
// names can repeat: two containers' processes are both host:1);
extern const char* const kClaimTokens;
// worker processes' heartbeats, for the operator (/metrics).
extern const char* const kWorkerHeartbeats;
// the stage a run is in (the SPH time loop, the FE check after it) and the
// FE check's outcome (docs/api.md, The FE stage); who submitted a job, for
// the queue quota (Limits::max_queued_per_client).
extern const char* const kStages;

// The SQL that differs between engines. Times are ISO 8601 UTC text with
// milliseconds and leases are on the database's clock, so every process
// sharing a database agrees.
struct Dialect {
  std::string now;             // the time now, as text
  std::string seconds_param;   // a `?` that takes seconds as a real number
  std::string lease_clock;     // now, in the type of the lease_until column
  std::string lease_in;        // lease_clock plus `?` seconds
  std::string time_ago;        // the time `?` seconds ago, as text
  std::string seconds_since;   // seconds from the text time in column `{}` to now
  std::string skip_locked;     // after a subquery that picks one row to claim
  std::string lock_row;        // after a SELECT of a row about to be changed
  std::string migration_lock;  // run first in the migration's transaction, or ""
  std::string submit_lock;     // run first in a submission under a queue quota, or ""
  // Migration i brings the schema from version i to i + 1.
  std::vector<std::string> migrations;
};

class Database {
 public:
  virtual ~Database() = default;
  virtual const Dialect& dialect() const = 0;
  // A connection of this thread's own, back to the pool when released.
  virtual std::unique_ptr<Connection> connect() = 0;
  // Whether the engine tells of changed jobs (PostgreSQL's LISTEN/NOTIFY);
  // if so, wait_for_change waits up to `timeout` for one (true) or none
  // (false). Without, the store is polled.
  virtual bool notifies() const { return false; }
  virtual bool wait_for_change(std::chrono::milliseconds) { return false; }
};

}  // namespace gearsph::server::sql
