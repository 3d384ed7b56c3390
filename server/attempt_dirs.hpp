#pragma once
// Where a run writes, and when its files become the job's results.
//
// Each claim of a job runs in a directory of its own,
// `jobs_dir/.attempts/ID.CLAIM`, and only a run whose fenced finish
// succeeded is published as `jobs_dir/ID` (one rename). A run that lost
// its claim (its worker frozen past the lease, cut off from the store, or
// stopped) writes nothing the API serves, and its directory is deleted.
// Should a worker die between its finish and the rename, whoever next
// resolves the job's directory completes the rename (results_dir).
//
// Runs without a claim token (Slurm's, whose scheduler fences them, and
// the jobs of stores older than the token) write `jobs_dir/ID` directly.
#include <filesystem>
#include <string>

#include "server/job_store.hpp"

namespace gearsph::server {

// jobs_dir/.attempts/ID.CLAIM
std::filesystem::path attempt_dir(const std::filesystem::path& jobs_dir, const std::string& id,
                                  const std::string& claim);

// Renames the attempt to jobs_dir/ID unless that exists already; true if
// jobs_dir/ID is there afterwards. Throws on a file-system error.
bool publish_attempt(const std::filesystem::path& jobs_dir, const std::string& id,
                     const std::string& claim);

// Deletes the attempt directories of job `id`, all but `keep` ("" for all).
// Never throws: what cannot be deleted stays for a later sweep.
void discard_attempts(const std::filesystem::path& jobs_dir, const std::string& id,
                      const std::string& keep = "");

// The directory whose files are the job's as the API serves them: the
// running attempt's while the job runs, the published one once it ended
// (publishing it first if its holder died before it could).
std::filesystem::path results_dir(const std::filesystem::path& jobs_dir, const JobRecord& job);

}  // namespace gearsph::server
