#pragma once
// The JSON documents the API answers with (OGC API - Processes shapes):
// job status info, links, identifiers.
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "server/job_store.hpp"
#include "solver/run/runner.hpp"

namespace gearsph::server {

inline constexpr const char* kProcessId = "gearsph-simulation";

// A random (version 4) UUID: job and study ids.
std::string new_id();
bool is_id(std::string_view s);

nlohmann::json link(const std::string& href, const std::string& rel, const std::string& type,
                    const std::string& title = "");

// The status info of a job; a running job's numbers come from `live`
// (the worker's memory) when given, being newer than the store's. With the
// FE check: `stage`, `fe_check` and `stage_wall_s` (docs/api.md, The FE stage).
nlohmann::json status_document(const JobRecord& job,
                               const std::optional<ProgressUpdate>& live = {});

// A job's `fe_check` member: the stage's state or outcome, null for a job
// without the check. `fe_check_json` as stored (ProgressUpdate), "" if none yet.
nlohmann::json fe_check_member(const JobRecord& job, const std::string& fe_check_json);

// `stage_wall_s`: the run's wall time in its parts.
nlohmann::json stage_wall(double wall_s, const nlohmann::json& fe_check);

// Percent 0-100 of a run (100 only when it is done).
int percent(std::int64_t step, std::int64_t steps);

}  // namespace gearsph::server
