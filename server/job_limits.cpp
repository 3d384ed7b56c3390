#include "server/job_limits.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#ifdef GEARSPH_WITH_RESULTS
#include "results/results_writer.hpp"
#endif

namespace gearsph::server {

namespace {

// history.csv: one text row per sample, ~25 characters a value; the
// runner's own columns (9) and the scene's, 16 leaving room.
constexpr double kCsvBytesPerValue = 25;
constexpr double kRunnerColumns = 16;
// Bytes per particle and frame of results.h5 without the results layer's own
// bound (results/results_writer.cpp, estimate_results_bytes): the frame
// fields of results/results_layout.hpp, uncompressed.
constexpr double kFrameBytesPerParticle = 136;
constexpr double kFixedBytes = 1 << 20;  // job.json, summary.json, the XDMF sidecar
// Output time (output_seconds), from runs of a plate of 315, 1,250 and
// 5,000 particles writing 200 to 2,000 frames on a 2-core machine with an
// SSD: 20, 24 and 41 ms a frame; and 200,000 history rows of 11 columns
// against 4,000: 0.65 s more.
constexpr double kSecondsPerFrame = 0.018;
constexpr double kSecondsPerFrameParticle = 4.5e-6;
constexpr double kSecondsPerHistoryValue = 0.45e-6;

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace

double output_seconds(double frames, double particles, double history_values) {
  return frames * (kSecondsPerFrame + particles * kSecondsPerFrameParticle) +
         history_values * kSecondsPerHistoryValue;
}

double output_seconds_of(const nlohmann::json& job, std::int64_t particles, std::int64_t steps) {
  const auto output = job.value("output", nlohmann::json::object());
  const double frames_asked = output.is_object() ? output.value("frames", 0.0) : 0.0;
  const double n = std::max(1.0, double(steps));
  // The default samples by time (job.hpp): at most one row every few steps.
  const double points =
      output.is_object() && output.contains("history_points")
          ? output.value("history_points", 0.0)
          : std::min(double(kDefaultHistoryPoints), n / double(kDefaultHistoryMinSteps));
  const double frames = frames_asked > 0 ? std::min(frames_asked, n) + 2 : 0.0;
  const double rows = std::min(points, n) + 2;
  return output_seconds(frames, double(particles), rows * kRunnerColumns);
}

nlohmann::json JobEstimate::to_json() const {
  return {{"particles", particles},
          {"steps", steps},
          {"frames", frames},
          {"particle_steps", particle_steps},
          {"disk_bytes", disk_bytes}};
}

JobEstimate estimate_job(const PreparedJob& job) {
  JobEstimate e;
  e.particles = static_cast<std::int64_t>(job.scene.sim.particles.n);
  e.steps = job.steps;
  e.frames = job.frames;
  e.particle_steps = double(e.particles) * double(e.steps);
  const double rows = double(job.steps / std::max<std::int64_t>(1, job.history_every) + 2);
  const double columns = double(job.scene.columns.size()) + kRunnerColumns;
#ifdef GEARSPH_WITH_RESULTS
  const double h5 = double(results::estimate_results_bytes(job));
#else
  const double h5 =
      double(e.frames) * double(e.particles) * kFrameBytesPerParticle + rows * columns * 8;
#endif
  e.disk_bytes = static_cast<std::uint64_t>(h5 + rows * columns * kCsvBytesPerValue + kFixedBytes);
  e.output_s = output_seconds(double(e.frames), double(e.particles), rows * columns);
  return e;
}

std::vector<JobIssue> over_limits(const JobEstimate& e, const Limits& limits) {
  std::vector<JobIssue> issues;
  if (e.particles > limits.max_particles) {
    issues.push_back({"/discretization", "the job has " + std::to_string(e.particles) +
                                             " particles; this server takes at most " +
                                             std::to_string(limits.max_particles) +
                                             ": use a coarser spacing"});
  }
  if (e.steps > limits.max_steps) {
    issues.push_back({"/time/end_s", "the job needs " + std::to_string(e.steps) +
                                         " time steps; this server takes at most " +
                                         std::to_string(limits.max_steps) +
                                         ": simulate less time or use a coarser spacing"});
  }
  if (e.particle_steps > limits.max_particle_steps) {
    issues.push_back({"/time/end_s", "the job needs " + number(e.particle_steps) +
                                         " particle-steps (particles x steps); this server takes "
                                         "at most " +
                                         number(limits.max_particle_steps)});
  }
  if (e.disk_bytes > limits.max_disk_bytes) {
    issues.push_back({"/output/frames",
                      "the results would take about " + number(double(e.disk_bytes) / 1e9) +
                          " GB on disk; this server takes at most " +
                          number(double(limits.max_disk_bytes) / 1e9) + " GB: write fewer frames"});
  }
  return issues;
}

JobEstimate estimate_job(const nlohmann::json& job, const JobSize& size) {
  JobEstimate e;
  e.particles = static_cast<std::int64_t>(size.particles);
  e.steps = static_cast<std::int64_t>(size.steps);
  const std::int64_t frames_asked = job.at("output").at("frames").get<std::int64_t>();
  // As prepare_job counts them: frame 0, one every steps/frames, the last.
  if (frames_asked > 0 && e.steps > 0) {
    const std::int64_t every =
        std::max<std::int64_t>(1, (e.steps + frames_asked - 1) / frames_asked);
    e.frames = 1 + e.steps / every + (e.steps % every ? 1 : 0);
  }
  e.particle_steps = double(e.particles) * double(e.steps);
  const double rows = std::min(double(kDefaultHistoryPoints), double(e.steps)) + 2;
  const double columns = 2 * kRunnerColumns;  // the scene's own: at most as many again
  const double h5 = double(e.frames) * double(e.particles) * kFrameBytesPerParticle;
  e.disk_bytes =
      static_cast<std::uint64_t>(h5 + rows * columns * (8 + kCsvBytesPerValue) + kFixedBytes);
  e.output_s = output_seconds_of(job, e.particles, e.steps);
  return e;
}

bool within_build_budget(const JobSize& size, const Limits& limits) {
  const double cost = size.body_fitted ? kBodyFittedBuildCost : 1.0;
  return size.particles * cost <= double(limits.max_built_particles);
}

nlohmann::json limits_json(const Limits& limits) {
  return {{"particles", limits.max_particles},
          {"steps", limits.max_steps},
          {"particle_steps", limits.max_particle_steps},
          {"disk_bytes", limits.max_disk_bytes},
          {"built_particles", limits.max_built_particles},
          {"built_particle_cost_body_fitted", kBodyFittedBuildCost}};
}

}  // namespace gearsph::server
