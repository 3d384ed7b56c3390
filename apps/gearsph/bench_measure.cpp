#include "apps/gearsph/bench_measure.hpp"

#include <malloc.h>
#include <sys/resource.h>

#include <cstdio>
#include <ctime>
#include <fstream>
#include <limits>
#include <sstream>

#include "solver/integrate/integrator.hpp"
#include "solver/job/job.hpp"
#include "solver/run/summary.hpp"

namespace gearsph::cli::bench {

namespace {

// Resident and peak resident memory of this process [bytes] (Linux).
struct Memory {
  double rss = 0, peak = 0;
};
Memory memory_now() {
  Memory m;
  std::ifstream f("/proc/self/status");
  std::string key;
  double kb = 0;
  std::string line;
  while (std::getline(f, line)) {
    std::istringstream s(line);
    s >> key >> kb;
    if (key == "VmRSS:") m.rss = 1024.0 * kb;
    if (key == "VmHWM:") m.peak = 1024.0 * kb;
  }
  return m;
}

// Starts a new peak (VmHWM) from the present resident memory, so that a
// case's peak is its own, not an earlier, larger case's (Linux 4.0+:
// clear_refs value 5). False where the kernel refuses.
bool reset_peak_memory() {
  std::ofstream f("/proc/self/clear_refs");
  f << "5";
  f.flush();
  return static_cast<bool>(f);
}

}  // namespace

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double children_cpu_seconds() {
  rusage ru{};
  getrusage(RUSAGE_CHILDREN, &ru);
  return double(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         1e-6 * double(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

json plate_job(double dx_m, double vf) {
  return {{"name", "bench-plate"},
          {"scene", {{"type", "plate"}, {"length_m", 0.2}, {"thickness_m", 0.02}, {"Vf", vf}}},
          {"discretization", {{"spacing_m", dx_m}}},
          {"output", {{"frames", 0}, {"history_points", 100}}}};
}

json gear_job() {
  return {{"name", "bench-gear"},
          {"scene", {{"type", "rack_pinion"}}},
          {"output", {{"frames", 0}, {"history_points", 1000}}}};
}

Timing time_steps(const json& job, int threads, std::int64_t steps) {
  // Baseline after handing back what earlier cases freed: the run's own
  // set-up trims the heap too (integrate::initialise), which would otherwise
  // count earlier cases' memory against this one.
  malloc_trim(0);
  const bool own_peak = reset_peak_memory();
  const Memory before = memory_now();
  PreparedJob pj = prepare_job(job, threads);
  Simulation& sim = pj.scene.sim;
  integrate::initialise(sim);
  integrate::step(sim);  // first touch of every scratch array
  sim.pass_times = PassTimes{};
  const auto w0 = Clock::now();
  const double c0 = cpu_seconds();
  for (std::int64_t s = 0; s < steps; ++s) integrate::step(sim);
  Timing t;
  t.cpu_s = cpu_seconds() - c0;
  t.wall_s = std::chrono::duration<double>(Clock::now() - w0).count();
  t.particles = sim.particles.n;
  t.pairs = sim.reference.entries() + sim.neighbours.entries() + sim.contacts.entries();
  t.steps = steps;
  t.dt = sim.dt;
  t.passes = pass_timing(sim.pass_times, steps);
  const Memory after = memory_now();
  t.rss_per_particle = (after.rss - before.rss) / double(t.particles);
  t.peak_per_particle = own_peak ? (after.peak - before.rss) / double(t.particles)
                                 : std::numeric_limits<double>::quiet_NaN();
  return t;
}

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

}  // namespace gearsph::cli::bench
