#pragma once
// The job store a command line names, above the engines that implement it
// (sql_sqlite.cpp, sql_postgres.cpp over job_store_sql.cpp): nothing below
// this file knows which engines there are.
#include <memory>
#include <string>

#include "server/job_store.hpp"

namespace gearsph::server {

// A store named on the command line (store_location.hpp): PostgreSQL by
// its URI or libpq's key=value form, or an SQLite file (sqlite:PATH or a
// plain path); anything else is refused (std::invalid_argument).
std::unique_ptr<JobStore> open_job_store(const std::string& location);

}  // namespace gearsph::server
