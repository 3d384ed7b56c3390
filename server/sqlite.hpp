#pragma once
// A thin RAII layer over the SQLite C API: connections, prepared statements,
// transactions and a pool that hands each thread a connection of its own.
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "server/connection_pool.hpp"

struct sqlite3;
struct sqlite3_stmt;

namespace gearsph::server::sqlite {

class Error : public std::runtime_error {
 public:
  Error(int result_code, const std::string& what) : std::runtime_error(what), code(result_code) {}
  int code;  // SQLite's primary or extended result code
};

class Statement {
 public:
  Statement(sqlite3* db, std::string_view sql);
  ~Statement();
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  // Parameters are numbered from 1, as in SQLite.
  Statement& bind(int index, std::int64_t value);
  Statement& bind(int index, int value) { return bind(index, static_cast<std::int64_t>(value)); }
  Statement& bind(int index, double value);
  Statement& bind(int index, std::string_view text);
  Statement& bind_null(int index);

  // Runs to the next row: true if a row is available, false when done.
  bool step();
  // Runs a statement that returns no rows.
  void run();

  // Columns are numbered from 0.
  int columns() const;
  // SQLITE_INTEGER, SQLITE_FLOAT, SQLITE_TEXT, SQLITE_BLOB or SQLITE_NULL.
  int type(int column) const;
  std::int64_t int64(int column) const;
  double real(int column) const;
  std::string text(int column) const;  // "" for NULL
  bool is_null(int column) const;

 private:
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
};

class Connection {
 public:
  // Opens (creating) the file in WAL mode with a busy timeout, foreign keys
  // on and synchronous=FULL: a committed submission survives a power cut.
  explicit Connection(const std::filesystem::path& file);
  ~Connection();
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  void exec(const std::string& sql);
  Statement prepare(std::string_view sql) { return Statement(db_, sql); }
  std::int64_t changes() const;
  sqlite3* handle() { return db_; }

 private:
  sqlite3* db_ = nullptr;
};

// Connections are opened on demand and reused; one thread holds a
// connection at a time (SQLite's WAL lets readers run beside the writer).
using Pool = ConnectionPool<Connection, std::filesystem::path>;

}  // namespace gearsph::server::sqlite
