#include "server/sql.hpp"

#include <cstdlib>

namespace gearsph::server::sql {

std::string Row::text(std::size_t column) const {
  const Value& v = cells_.at(column);
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  if (const auto* i = std::get_if<std::int64_t>(&v)) return std::to_string(*i);
  if (const auto* d = std::get_if<double>(&v)) return std::to_string(*d);
  return {};
}

std::int64_t Row::int64(std::size_t column) const {
  const Value& v = cells_.at(column);
  if (const auto* i = std::get_if<std::int64_t>(&v)) return *i;
  if (const auto* d = std::get_if<double>(&v)) return static_cast<std::int64_t>(*d);
  if (const auto* s = std::get_if<std::string>(&v)) return std::strtoll(s->c_str(), nullptr, 10);
  return 0;
}

double Row::real(std::size_t column) const {
  const Value& v = cells_.at(column);
  if (const auto* d = std::get_if<double>(&v)) return *d;
  if (const auto* i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
  if (const auto* s = std::get_if<std::string>(&v)) return std::strtod(s->c_str(), nullptr);
  return 0.0;
}

Transaction::~Transaction() {
  if (done_) return;
  try {
    db_.rollback();
  } catch (...) {  // a destructor must not throw; the engine rolls back a broken connection
  }
}

const char* const kClaimTokens = R"sql(
ALTER TABLE jobs ADD COLUMN claim TEXT;
)sql";

const char* const kWorkerHeartbeats = R"sql(
CREATE TABLE workers (
  name    TEXT PRIMARY KEY,
  started TEXT NOT NULL,
  seen    TEXT NOT NULL,
  running INTEGER NOT NULL DEFAULT 0
);
CREATE INDEX jobs_by_finished ON jobs(finished);
)sql";

const char* const kStages = R"sql(
ALTER TABLE jobs ADD COLUMN stage TEXT;
ALTER TABLE jobs ADD COLUMN fe_check TEXT;
ALTER TABLE jobs ADD COLUMN client TEXT;
CREATE INDEX jobs_by_client ON jobs(client) WHERE status = 'accepted';
)sql";

}  // namespace gearsph::server::sql
