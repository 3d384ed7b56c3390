#include "server/postgres.hpp"

#include <poll.h>

#include <libpq-fe.h>

#include <cstdio>
#include <cstdlib>

namespace gearsph::server::postgres {

namespace {

// libpq's messages end with a newline; ours do not.
std::string trimmed(const char* message) {
  std::string s = message ? message : "";
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

}  // namespace

Param param(std::string_view text) {
  return std::string(text);
}

Param param(std::int64_t value) {
  return std::to_string(value);
}

Param param(int value) {
  return std::to_string(value);
}

Param param(double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", value);
  return std::string(buf);
}

Result::~Result() {
  if (r_) PQclear(r_);
}

int Result::rows() const {
  return PQntuples(r_);
}

int Result::columns() const {
  return PQnfields(r_);
}

std::int64_t Result::affected() const {
  const char* n = PQcmdTuples(r_);
  return n && *n ? std::strtoll(n, nullptr, 10) : 0;
}

bool Result::is_null(int row, int column) const {
  return PQgetisnull(r_, row, column) != 0;
}

std::string Result::text(int row, int column) const {
  if (PQgetisnull(r_, row, column)) return {};
  return std::string(PQgetvalue(r_, row, column),
                     static_cast<std::size_t>(PQgetlength(r_, row, column)));
}

std::int64_t Result::int64(int row, int column) const {
  return std::strtoll(PQgetvalue(r_, row, column), nullptr, 10);
}

double Result::real(int row, int column) const {
  return std::strtod(PQgetvalue(r_, row, column), nullptr);
}

Connection::Connection(const std::string& uri) : c_(PQconnectdb(uri.c_str())) {
  if (!c_ || PQstatus(c_) != CONNECTION_OK) {
    const std::string message = c_ ? trimmed(PQerrorMessage(c_)) : "out of memory";
    PQfinish(c_);
    c_ = nullptr;
    throw Error("", "cannot connect to the job store: " + message);
  }
  // Notices (e.g. "relation already exists, skipping") are not errors.
  PQsetNoticeProcessor(
      c_, [](void*, const char*) {}, nullptr);
}

Connection::~Connection() {
  if (c_) PQfinish(c_);
}

bool Connection::wait_for_notification(int timeout_ms) {
  auto drain = [&] {
    bool any = false;
    while (PGnotify* n = PQnotifies(c_)) {
      PQfreemem(n);
      any = true;
    }
    return any;
  };
  if (drain()) return true;
  pollfd fd{PQsocket(c_), POLLIN, 0};
  if (fd.fd < 0) throw Error("", "job store: the listening connection is closed");
  const int ready = ::poll(&fd, 1, timeout_ms);
  if (ready < 0) return false;  // a signal: the caller waits again
  if (ready > 0 && PQconsumeInput(c_) == 0) {
    throw Error("", "job store: " + trimmed(PQerrorMessage(c_)));
  }
  return drain();
}

bool Connection::ok() const {
  return c_ && PQstatus(c_) == CONNECTION_OK;
}

Result Connection::exec(const std::string& sql, const std::vector<Param>& params) {
  std::vector<const char*> values;
  values.reserve(params.size());
  for (const Param& p : params) values.push_back(p ? p->c_str() : nullptr);
  auto run = [&] {
    // Without parameters, the simple protocol: it also runs several
    // statements at once (the migrations).
    return params.empty() ? PQexec(c_, sql.c_str())
                          : PQexecParams(c_, sql.c_str(), static_cast<int>(values.size()), nullptr,
                                         values.data(), nullptr, nullptr, 0);
  };
  const bool outside_transaction = PQtransactionStatus(c_) == PQTRANS_IDLE;
  pg_result* r = run();
  ExecStatusType status = r ? PQresultStatus(r) : PGRES_FATAL_ERROR;
  if (status != PGRES_COMMAND_OK && status != PGRES_TUPLES_OK && outside_transaction &&
      PQstatus(c_) == CONNECTION_BAD) {
    // The database restarted since this pooled connection was last used:
    // connect again and retry once. Only outside a transaction, whose
    // earlier statements died with the old connection.
    if (r) PQclear(r);
    PQreset(c_);
    r = PQstatus(c_) == CONNECTION_OK ? run() : nullptr;
    status = r ? PQresultStatus(r) : PGRES_FATAL_ERROR;
  }
  if (status == PGRES_COMMAND_OK || status == PGRES_TUPLES_OK) return Result(r);
  const char* state = r ? PQresultErrorField(r, PG_DIAG_SQLSTATE) : nullptr;
  Error error(state ? state : "",
              "job store: " + trimmed(r ? PQresultErrorMessage(r) : PQerrorMessage(c_)));
  if (r) PQclear(r);
  throw error;
}

}  // namespace gearsph::server::postgres
