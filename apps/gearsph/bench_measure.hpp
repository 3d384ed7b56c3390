#pragma once
// What `gearsph bench` and `gearsph bench pareto` measure with: CPU time,
// the bench's two jobs (the oscillating plate and the seed paper's gear), and
// bare time steps with the memory they hold.
//
// Timings are wall clock and process CPU time. The machine may be shared:
// every comparison is measured in the same run, interleaved, best of the
// repeats, and CPU time is printed beside wall time so that a loaded machine
// shows as wall >> CPU rather than as a slow code.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

namespace gearsph::cli::bench {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

// CPU time of this process, and of its children that have ended [s].
double cpu_seconds();
double children_cpu_seconds();

// The oscillating plate of validation.md section 5 (and PySPH's example):
// L 0.2 m, H 0.02 m, E 2 MPa, nu 0.3975, rho 1000, clamp L/4.
json plate_job(double dx_m, double vf = 0.01);

// The seed paper's gear case: every field at its default.
json gear_job();

struct Timing {
  std::size_t particles = 0;
  std::size_t pairs = 0;  // directed pair entries evaluated per step (i-j and j-i)
  std::int64_t steps = 0;
  double dt = 0, wall_s = 0, cpu_s = 0;
  double rss_per_particle = 0, peak_per_particle = 0;  // [bytes]
  json passes;  // the step's passes, timed (summary's `timing`)
  double particle_steps_per_s() const { return double(particles) * double(steps) / wall_s; }
  double pairs_per_s() const { return double(pairs) * double(steps) / wall_s; }
  double ns_per_particle_step() const { return 1e9 * wall_s / (double(particles) * double(steps)); }
  double cpu_ns_per_particle_step() const {
    return 1e9 * cpu_s / (double(particles) * double(steps));
  }
};

// Bare time steps, no history, output or peak tracking: what the solver
// itself costs. Setup (scene, stable step, reference pairs) is not timed.
Timing time_steps(const json& job, int threads, std::int64_t steps);

// One number printed with a printf format.
std::string fmt(const char* f, double v);

}  // namespace gearsph::cli::bench
