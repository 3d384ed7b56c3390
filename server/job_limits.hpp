#pragma once
// How big a job is, and whether this server takes it: particles, time
// steps, their product (the work) and the disk its results will need.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "server/config.hpp"
#include "solver/job/job.hpp"
#include "solver/job/job_size.hpp"

namespace gearsph::server {

struct JobEstimate {
  std::int64_t particles = 0;
  std::int64_t steps = 0;
  std::int64_t frames = 0;
  double particle_steps = 0.0;
  std::uint64_t disk_bytes = 0;
  double output_s = 0.0;  // writing frames and histories (output_seconds)
  nlohmann::json to_json() const;
};

// Seconds a run spends writing its output, apart from computing: each
// frame of results.h5 (with its XDMF entry, flushed so a crash loses
// nothing) and each history value. Measured on a 2-core machine
// (docs/api.md, Preview): a tiny plate writing 2,000 frames took 46 s
// instead of 1.5 s.
double output_seconds(double frames, double particles, double history_values);
// The same for a job of the store (its job document with every default
// filled in, its particle and step counts).
double output_seconds_of(const nlohmann::json& job, std::int64_t particles, std::int64_t steps);

JobEstimate estimate_job(const PreparedJob& job);

// One issue per exceeded limit, each at the pointer of the field to change.
std::vector<JobIssue> over_limits(const JobEstimate& e, const Limits& limits);

// Before the scene is built: the same from the solver's estimate of its
// particles and steps (gearsph::estimate_job_size), for a job (validated,
// defaults filled) whose scene a request does not build.
JobEstimate estimate_job(const nlohmann::json& job, const JobSize& size);

// Whether a request may build the job's scene: its estimated particles
// within Limits::max_built_particles, a body-fitted particle counting
// kBodyFittedBuildCost (its relaxation: about 3.4 ms on one core of a
// 2-core machine, against 33 us for a lattice particle with its pairs and
// stable step: 4.0 s for 1,190 rack_pinion particles, 66 s for a 2-million
// particle plate).
inline constexpr double kBodyFittedBuildCost = 100.0;
bool within_build_budget(const JobSize& size, const Limits& limits);

nlohmann::json limits_json(const Limits& limits);

}  // namespace gearsph::server
