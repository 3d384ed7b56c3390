#pragma once
// A thin RAII layer over libpq: connections, results, transactions and a
// pool that hands each thread a connection of its own. Parameters travel
// as text ($1, $2, ... in the SQL); a connection that broke (the database
// restarted) is dropped instead of going back to the pool.
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "server/connection_pool.hpp"

struct pg_conn;
struct pg_result;

namespace gearsph::server::postgres {

class Error : public std::runtime_error {
 public:
  Error(std::string state, const std::string& what)
      : std::runtime_error(what), sqlstate(std::move(state)) {}
  std::string sqlstate;  // e.g. "40001"; "" when the connection failed
};

// One parameter: text, or NULL.
using Param = std::optional<std::string>;
using Params = std::vector<Param>;
Param param(std::string_view text);
Param param(std::int64_t value);
Param param(int value);
Param param(double value);

class Result {
 public:
  explicit Result(pg_result* r) : r_(r) {}
  ~Result();
  Result(Result&& other) noexcept : r_(other.r_) { other.r_ = nullptr; }
  Result& operator=(Result&&) = delete;
  Result(const Result&) = delete;
  Result& operator=(const Result&) = delete;

  int rows() const;
  int columns() const;
  std::int64_t affected() const;  // rows changed by INSERT / UPDATE / DELETE
  bool is_null(int row, int column) const;
  std::string text(int row, int column) const;  // "" for NULL
  std::int64_t int64(int row, int column) const;
  double real(int row, int column) const;

 private:
  pg_result* r_;
};

class Connection {
 public:
  explicit Connection(const std::string& uri);
  ~Connection();
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  Result exec(const std::string& sql, const std::vector<Param>& params = {});
  bool ok() const;
  // After LISTEN: waits up to timeout_ms for notifications; true if any
  // came (all are consumed). Throws if the connection is lost.
  bool wait_for_notification(int timeout_ms);

 private:
  pg_conn* c_ = nullptr;
};

using Pool = ConnectionPool<Connection, std::string>;

}  // namespace gearsph::server::postgres
