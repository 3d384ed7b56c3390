#include "server/attempt_dirs.hpp"

namespace gearsph::server {

namespace fs = std::filesystem;

namespace {

constexpr const char* kAttempts = ".attempts";

}  // namespace

fs::path attempt_dir(const fs::path& jobs_dir, const std::string& id, const std::string& claim) {
  return jobs_dir / kAttempts / (id + "." + claim);
}

bool publish_attempt(const fs::path& jobs_dir, const std::string& id, const std::string& claim) {
  const fs::path published = jobs_dir / id;
  std::error_code ec;
  if (fs::exists(published, ec)) return true;
  const fs::path from = attempt_dir(jobs_dir, id, claim);
  if (!fs::exists(from, ec)) return false;
  // rename(2) onto a name that does not exist: atomic, and a second
  // publisher racing this one fails with EEXIST / ENOTEMPTY, not a mix.
  fs::rename(from, published, ec);
  if (ec && !fs::exists(published)) throw fs::filesystem_error("publishing", from, published, ec);
  return true;
}

void discard_attempts(const fs::path& jobs_dir, const std::string& id, const std::string& keep) {
  std::error_code ec;
  const std::string prefix = id + ".";
  for (fs::directory_iterator it(jobs_dir / kAttempts, ec), end; !ec && it != end;
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0 || name == prefix + keep) continue;
    std::error_code gone;
    fs::remove_all(it->path(), gone);
  }
}

fs::path results_dir(const fs::path& jobs_dir, const JobRecord& job) {
  const fs::path published = jobs_dir / job.id;
  if (job.claim.empty()) return published;
  if (job.status == JobStatus::running || job.status == JobStatus::accepted) {
    return attempt_dir(jobs_dir, job.id, job.claim);
  }
  if (job.status == JobStatus::successful || job.status == JobStatus::failed) {
    try {
      publish_attempt(jobs_dir, job.id, job.claim);
    } catch (const fs::filesystem_error&) {
      // The files stay where they are; the listing shows none until a
      // later request publishes them.
    }
  }
  return published;
}

}  // namespace gearsph::server
