#include "server/open_job_store.hpp"

#include "server/store_location.hpp"

namespace gearsph::server {

std::unique_ptr<JobStore> open_job_store(const std::string& location) {
  const StoreLocation where = parse_store_location(location);
  if (where.engine == StoreEngine::postgresql) return open_postgres_job_store(where.target);
  return open_sqlite_job_store(where.target);
}

}  // namespace gearsph::server
