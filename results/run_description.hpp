#pragma once
// The parts of results.h5 written once, when the run starts: /meta (what was
// run, by which solver, in which units), /bodies and /initial.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "results/h5_util.hpp"
#include "solver/job/job.hpp"

namespace gearsph::results {

// /meta with every attribute but `units`; status "running".
void write_meta(hid_t file, const PreparedJob& job);
// The `units` attribute, once the history columns are known.
void write_units(hid_t file, const std::vector<std::string>& history_datasets);
nlohmann::json units_json(const std::vector<std::string>& history_datasets);
// Rewrites status and steps_done in place (the attributes keep their size).
void write_status(hid_t file, const std::string& status, std::int64_t steps_done);

void write_bodies(hid_t file, const Simulation& sim);
void write_initial(hid_t file, const Particles& p);

// Now, as ISO 8601 UTC (2024-05-01T12:00:00Z).
std::string utc_now();

}  // namespace gearsph::results
