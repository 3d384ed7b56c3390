#pragma once
// How big a job is, and whether this server takes it: particles, time
// steps, their product (the work) and the disk its results will need.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "server/config.hpp"
#include "solver/job/job.hpp"

namespace gearsph::server {

struct JobEstimate {
  std::int64_t particles = 0;
  std::int64_t steps = 0;
  std::int64_t frames = 0;
  double particle_steps = 0.0;
  std::uint64_t disk_bytes = 0;
  nlohmann::json to_json() const;
};

JobEstimate estimate_job(const PreparedJob& job);

// One issue per exceeded limit, each at the pointer of the field to change.
std::vector<JobIssue> over_limits(const JobEstimate& e, const Limits& limits);

// Before the scene is built: a lower bound of the particle count from the
// scene's lengths and the spacing, so a job asking for billions of
// particles is refused before building them exhausts memory. 0 when the
// job gives no spacing (the scene then picks a modest one).
double particles_lower_bound(const nlohmann::json& job);
// The sentence that refuses a job whose lower bound is over the limit.
std::string too_many_particles(double lower_bound, const Limits& limits);

nlohmann::json limits_json(const Limits& limits);

}  // namespace gearsph::server
