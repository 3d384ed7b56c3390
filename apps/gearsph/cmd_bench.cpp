// gearsph bench: the speed numbers of issue 7 side by side in one run
// (throughput of the plate and the gear case at 1 and 2 threads, PySPH on
// the same plate, cost per particle-step from 1e3 to 1e6 particles, memory
// per particle, the paper's full case), and `gearsph bench pareto`: error
// against cost over kernel, spacing, h/dx, Courant number and formulation.
// docs/speed-accuracy.md explains every number and records measured ones.
//
// Timings are wall clock and process CPU time. The machine may be shared:
// every comparison is measured in the same run, interleaved, best of the
// repeats, and CPU time is printed beside wall time so that a loaded machine
// shows as wall >> CPU rather than as a slow code.
#include <malloc.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/gearsph/cli.hpp"
#include "solver/integrate/integrator.hpp"
#include "solver/job/job.hpp"
#include "solver/run/execute.hpp"
#include "solver/run/runner.hpp"
#ifdef GEARSPH_WITH_RENDER
#ifdef GEARSPH_WITH_SERVICE
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>

#include <thread>

#include "server/http_client.hpp"
#endif
#include "render/plot_image.hpp"
#include "render/png_io.hpp"
#endif

namespace gearsph::cli {

namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

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

// The oscillating plate of validation.md section 5 (and PySPH's example):
// L 0.2 m, H 0.02 m, E 2 MPa, nu 0.3975, rho 1000, clamp L/4.
json plate_job(double dx_m, double vf = 0.01) {
  return {{"name", "bench-plate"},
          {"scene", {{"type", "plate"}, {"length_m", 0.2}, {"thickness_m", 0.02}, {"Vf", vf}}},
          {"discretization", {{"spacing_m", dx_m}}},
          {"output", {{"frames", 0}, {"history_points", 100}}}};
}

// The paper's gear case: every field at its default.
json gear_job() {
  return {{"name", "bench-gear"},
          {"scene", {{"type", "rack_pinion"}}},
          {"output", {{"frames", 0}, {"history_points", 1000}}}};
}

struct Timing {
  std::size_t particles = 0;
  std::size_t pairs = 0;  // directed pair entries evaluated per step (i-j and j-i)
  std::int64_t steps = 0;
  double dt = 0, wall_s = 0, cpu_s = 0;
  double rss_per_particle = 0, peak_per_particle = 0;  // [bytes]
  double particle_steps_per_s() const { return double(particles) * double(steps) / wall_s; }
  double pairs_per_s() const { return double(pairs) * double(steps) / wall_s; }
  double ns_per_particle_step() const { return 1e9 * wall_s / (double(particles) * double(steps)); }
  double cpu_ns_per_particle_step() const {
    return 1e9 * cpu_s / (double(particles) * double(steps));
  }
};

// Bare time steps, no history, output or peak tracking: what the solver
// itself costs. Setup (scene, stable step, reference pairs) is not timed.
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

// ---------------------------------------------------------------- PySPH

// bench/pysph_plate.py next to the source tree the binary was built in
// (build dirs live inside it), or --pysph-script.
std::filesystem::path find_pysph_script(const std::optional<std::string>& given) {
  if (given) return *given;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  for (std::filesystem::path d = exe.parent_path(); !d.empty() && d != d.root_path();
       d = d.parent_path()) {
    const std::filesystem::path s = d / "bench" / "pysph_plate.py";
    if (std::filesystem::exists(s)) return s;
  }
  return {};
}

struct PysphResult {
  bool ok = false;
  std::string message;
  json report;  // the script's JSON line
  double cpu_s = 0;
};

PysphResult run_pysph(const std::string& python, const std::filesystem::path& script,
                      const std::filesystem::path& dir, double vf, double end_s, int every) {
  PysphResult r;
  std::filesystem::create_directories(dir);
  const std::string cmd = "OMP_NUM_THREADS=1 " + python + " '" + script.string() + "' --vf " +
                          fmt("%.6g", vf) + " --tf " + fmt("%.9g", end_s) + " --pfreq " +
                          std::to_string(every) + " -d '" + dir.string() + "/out' > '" +
                          dir.string() + "/log.txt' 2>&1";
  const double c0 = children_cpu_seconds();
  const int rc = std::system(cmd.c_str());
  r.cpu_s = children_cpu_seconds() - c0;
  std::ifstream log(dir / "log.txt");
  std::string line, last;
  while (std::getline(log, line)) {
    if (!line.empty() && line.front() == '{') last = line;
  }
  if (rc != 0 || last.empty()) {
    r.message =
        "PySPH run failed (exit " + std::to_string(rc) + "); see " + dir.string() + "/log.txt";
    return r;
  }
  r.report = json::parse(last);
  r.ok = r.report.value("run_s", json()).is_number();
  if (!r.ok) r.message = "PySPH printed no run time";
  return r;
}

// ---------------------------------------------------------------- study

#ifdef GEARSPH_WITH_SERVICE
// `gearsph serve` in a child process on a fresh data directory, at its
// defaults (the cores a budget the jobs share); stopped with SIGTERM.
class ServeChild {
 public:
  explicit ServeChild(const std::filesystem::path& dir) : dir_(dir) {
    std::filesystem::create_directories(dir_);
    std::error_code ec;
    const std::string self = std::filesystem::read_symlink("/proc/self/exe", ec).string();
    const std::string data = (dir_ / "data").string(), log = (dir_ / "serve.log").string();
    pid_ = ::fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {
      const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(fd, 1);
      ::dup2(fd, 2);
      ::execl(self.c_str(), self.c_str(), "serve", "--port", "0", "--data", data.c_str(),
              static_cast<char*>(nullptr));
      ::_exit(127);
    }
    const std::string marker = "listening on http://";
    for (int k = 0; k < 3000 && port_.empty(); ++k) {
      std::ifstream in(log);
      const std::string text((std::istreambuf_iterator<char>(in)), {});
      const auto at = text.find(marker);
      const auto colon = at == std::string::npos ? at : text.find(':', at + marker.size());
      const auto end = colon == std::string::npos ? colon : text.find_first_of(" \n", colon);
      if (end != std::string::npos) {
        host_ = text.substr(at + marker.size(), colon - at - marker.size());
        port_ = text.substr(colon + 1, end - colon - 1);
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    }
    if (port_.empty()) throw std::runtime_error("gearsph serve did not start; see " + log);
  }
  ~ServeChild() {
    ::kill(pid_, SIGTERM);
    int status = 0;
    ::waitpid(pid_, &status, 0);
  }
  ServeChild(const ServeChild&) = delete;
  ServeChild& operator=(const ServeChild&) = delete;
  const std::string& host() const { return host_; }
  const std::string& port() const { return port_; }

 private:
  std::filesystem::path dir_;
  pid_t pid_ = -1;
  std::string host_, port_;
};

// Seconds of an RFC 3339 UTC time as the job store writes it
// (2026-11-26T07:55:08.140Z); NaN if it is not one.
double utc_seconds(const std::string& t) {
  std::tm tm{};
  double sec = 0.0;
  if (std::sscanf(t.c_str(), "%d-%d-%dT%d:%d:%lfZ", &tm.tm_year, &tm.tm_mon, &tm.tm_mday,
                  &tm.tm_hour, &tm.tm_min, &sec) != 6) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  tm.tm_year -= 1900;
  tm.tm_mon -= 1;
  return double(timegm(&tm)) + sec;
}

// A study of `jobs` copies of the paper's case (the first `end_s` of it)
// submitted at once to `gearsph serve` at its defaults: how long the
// study takes against one job's time, and jobs per hour.
json study_throughput(const std::filesystem::path& dir, int jobs, double end_s) {
  ServeChild serve(dir);
  server::HttpClient c(serve.host(), serve.port(), std::chrono::seconds(60));
  json base = {{"scene", {{"type", "rack_pinion"}}}, {"time", {{"end_s", end_s}}}};
  json names = json::array();
  for (int k = 1; k <= jobs; ++k) names.push_back("paper-" + std::to_string(k));
  const json study = {
      {"name", "bench"}, {"base", base}, {"axes", {{{"pointer", "/name"}, {"values", names}}}}};
  const auto t0 = Clock::now();
  const server::ClientResponse r = c.post_json("/studies", study.dump());
  if (r.status != 201) throw std::runtime_error("the study was refused: " + r.body);
  const std::string id = r.json().at("studyID");
  json done;
  for (;;) {
    done = c.get("/studies/" + id).json();
    const std::string status = done.at("status");
    if (status != "accepted" && status != "running") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  // A job's time: claimed to finished (set-up, run and results), as the
  // store records it; the run's own wall time beside it.
  double job_time = 0.0, run_wall = 0.0;
  int one_thread = 0, ok = 0;
  for (const json& j : done.at("jobs")) {
    const std::string job_id = j.at("jobID");
    const server::ClientResponse s = c.get("/jobs/" + job_id + "/files/summary.json");
    const json record = c.get("/jobs/" + job_id).json();
    if (s.status != 200 || !record.at("finished").is_string()) continue;
    const json summary = s.json();
    ++ok;
    run_wall += summary.at("wall_s").get<double>();
    job_time += utc_seconds(record.at("finished")) - utc_seconds(record.at("started"));
    one_thread += summary.at("threads").get<int>() == 1 ? 1 : 0;
  }
  const json health = c.get("/health").json();
  const double mean = job_time / std::max(ok, 1);
  const int cores = health.value("core_budget", 0) > 0 ? health.at("core_budget").get<int>()
                                                       : health.at("workers").get<int>();
  return {{"jobs", jobs},
          {"end_s", end_s},
          {"status", done.at("status")},
          {"completed", ok},
          {"cores", cores},
          {"core_budget", health.value("core_budget", 0)},
          {"jobs_on_one_thread", one_thread},
          {"study_wall_s", wall},
          {"mean_job_time_s", mean},
          {"mean_run_wall_s", run_wall / std::max(ok, 1)},
          {"job_times", wall / mean},
          {"ideal_job_times", double(jobs) / cores},
          {"jobs_per_hour", 3600.0 * jobs / wall}};
}
#endif

// ---------------------------------------------------------------- bench

int bench_main(Args& args) {
  const bool quick = args.flag("quick");
  const bool no_pysph = args.flag("no-pysph");
  const bool skip_full = args.flag("skip-full");
  [[maybe_unused]] const bool skip_study = args.flag("skip-study");
  [[maybe_unused]] const int study_jobs = args.integer("study-jobs", 16);
  const std::string out = args.option("out").value_or("bench");
  const std::string python = args.option("python").value_or("/usr/bin/python3");
  const auto script_opt = args.option("pysph-script");
  const int repeats = args.integer("repeats", quick ? 2 : 3);
  const double max_particles = std::stod(args.option("max-particles").value_or("1e6"));
  args.positional();
  std::filesystem::create_directories(out);
  json report;
  report["quick"] = quick;
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) == 3) report["load_average_1min"] = load[0];
  std::printf("gearsph bench%s: load average %.2f (on a shared machine read the ratios)\n\n",
              quick ? " --quick" : "", load[0]);

  // 1. Throughput at 1 and 2 threads, interleaved, best of `repeats`.
  struct Case {
    std::string name;
    json job;
    std::int64_t steps;
  };
  // The fine plate (0.3 mm, ~56,000 particles) shows the threads where a
  // step is long enough that barriers do not dominate.
  const std::vector<Case> cases = {{"plate", plate_job(0.002), quick ? 1000 : 4000},
                                   {"gear", gear_job(), quick ? 2000 : 10000},
                                   {"plate-fine", plate_job(0.0003), quick ? 40 : 150}};
  const std::array<int, 2> thread_counts = {1, 2};
  std::vector<std::array<Timing, 2>> best(cases.size());
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t c = 0; c < cases.size(); ++c) {
      for (std::size_t t = 0; t < thread_counts.size(); ++t) {
        const Timing x = time_steps(cases[c].job, thread_counts[t], cases[c].steps);
        if (r == 0 || x.wall_s < best[c][t].wall_s) best[c][t] = x;
      }
    }
  }
  std::printf("1. Throughput (bare time steps, best of %d)\n", repeats);
  // cpu ns/p-st: CPU time of all threads per particle-step; on a quiet
  // machine wall * threads ~ CPU, on a loaded one wall >> CPU / threads.
  std::printf("%-10s %7s %9s %7s %8s %8s %8s %11s %10s %8s %12s\n", "case", "threads", "particles",
              "pairs", "steps", "wall_s", "cpu_s", "Mpart-st/s", "Mpairs/s", "speed-up",
              "cpu ns/p-st");
  json thr = json::array();
  for (std::size_t c = 0; c < cases.size(); ++c) {
    for (std::size_t t = 0; t < thread_counts.size(); ++t) {
      const Timing& x = best[c][t];
      const double speedup = best[c][0].wall_s / x.wall_s;
      std::printf("%-10s %7d %9zu %7zu %8lld %8.3f %8.3f %11.3f %10.2f %8.2f %12.1f\n",
                  cases[c].name.c_str(), thread_counts[t], x.particles, x.pairs,
                  static_cast<long long>(x.steps), x.wall_s, x.cpu_s,
                  1e-6 * x.particle_steps_per_s(), 1e-6 * x.pairs_per_s(), speedup,
                  x.cpu_ns_per_particle_step());
      thr.push_back({{"case", cases[c].name},
                     {"threads", thread_counts[t]},
                     {"particles", x.particles},
                     {"pairs_per_step", x.pairs},
                     {"steps", x.steps},
                     {"dt_s", x.dt},
                     {"wall_s", x.wall_s},
                     {"cpu_s", x.cpu_s},
                     {"particle_steps_per_s", x.particle_steps_per_s()},
                     {"pair_interactions_per_s", x.pairs_per_s()},
                     {"speedup_vs_1_thread", speedup},
                     {"cpu_ns_per_particle_step", x.cpu_ns_per_particle_step()}});
    }
  }
  report["throughput"] = thr;
  std::printf("\n");

  // 2. PySPH's oscillating plate against ours, on PySPH's settings (dx 2 mm,
  // cubic spline, h 1.3 dx, dt 1e-5 s, Vf 0.01, one thread each), three
  // ways: bare steps; a run in this process (stepping, history, analysis);
  // and `gearsph run` as a user runs it, the whole process with the default
  // output (start-up, set-up, 50 frames, history, summary). PySPH is timed
  // by its own "Run took" (its time loop, without start-up or compilation).
  {
    const double dt = 1e-5, vf = 0.01;
    // 2000 steps (issue 30's case); the full bench runs past one period
    // (three zero crossings with a 10 % long period) for the period error.
    const double end_s = quick ? 0.02 : 0.32;
    json ours_job = plate_job(0.002, vf);
    ours_job["discretization"]["kernel"] = "cubic_spline";
    ours_job["discretization"]["h_over_dx"] = 1.3;
    ours_job["time"] = {{"dt_s", dt}, {"end_s", end_s}};
    ours_job["output"]["history_points"] = quick ? 100 : 3200;
    PreparedJob pj = prepare_job(ours_job, 1);
    const std::size_t n_ours = pj.scene.sim.particles.n;
    const std::int64_t planned_steps = pj.steps;
    const RunResult ours = run_job(pj);
    const double ours_rate = double(n_ours) * double(ours.steps_done) / ours.wall_s;
    Timing bare;
    for (int r = 0; r < repeats; ++r) {
      const Timing x = time_steps(ours_job, 1, std::min<std::int64_t>(planned_steps, 4000));
      if (r == 0 || x.wall_s < bare.wall_s) bare = x;
    }
    // The user's run: the job file as written, every output at its default.
    json user_job = ours_job;
    user_job.erase("output");
    const std::filesystem::path user_dir = std::filesystem::path(out) / "plate_user_run";
    const std::filesystem::path user_file = std::filesystem::path(out) / "plate_user_job.json";
    std::ofstream(user_file) << user_job.dump(2) << "\n";
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    const std::string user_cmd = "'" + self.string() + "' run '" + user_file.string() +
                                 "' --out '" + user_dir.string() + "' --threads 1 --quiet";
    double user_s = std::numeric_limits<double>::infinity();
    bool user_ok = true;
    for (int r = 0; r < repeats && user_ok; ++r) {
      std::filesystem::remove_all(user_dir, ec);
      const auto t0 = Clock::now();
      user_ok = std::system(user_cmd.c_str()) == 0;
      user_s = std::min(user_s, std::chrono::duration<double>(Clock::now() - t0).count());
    }
    const double user_rate = double(n_ours) * double(planned_steps) / user_s;
    const json& a = ours.summary.at("analysis");
    json row = {{"dt_s", dt},
                {"end_s", end_s},
                {"Vf", vf},
                {"kernel", "cubic_spline"},
                {"h_over_dx", 1.3},
                {"bare",
                 {{"particles", bare.particles},
                  {"steps", bare.steps},
                  {"wall_s", bare.wall_s},
                  {"particle_steps_per_s", bare.particle_steps_per_s()}}},
                {"ours",
                 {{"particles", n_ours},
                  {"steps", ours.steps_done},
                  {"wall_s", ours.wall_s},
                  {"particle_steps_per_s", ours_rate},
                  {"period_s", a.value("period_s", json())},
                  {"period_error", a.value("period_error", json())}}},
                {"user_run",
                 {{"command", user_cmd},
                  {"ok", user_ok},
                  {"particles", n_ours},
                  {"steps", planned_steps},
                  {"process_wall_s", user_s},
                  {"particle_steps_per_s", user_rate}}}};
    std::printf(
        "2. Oscillating plate, ours against PySPH (dx 2 mm, cubic spline, h 1.3 dx, dt %.0e s, "
        "Vf %.2f, %g s, 1 thread)\n",
        dt, vf, end_s);
    std::printf("%-34s %9s %8s %9s %12s %12s\n", "code", "particles", "steps", "wall_s",
                "Mpart-st/s", "period_err");
    auto perr = [](const json& v) {
      return v.is_number() ? fmt("%+.2f%%", 100.0 * v.get<double>()) : std::string("n/a");
    };
    std::printf("%-34s %9zu %8lld %9.3f %12.3f %12s\n", "gearsph, bare steps", bare.particles,
                static_cast<long long>(bare.steps), bare.wall_s, 1e-6 * bare.particle_steps_per_s(),
                "");
    std::printf("%-34s %9zu %8lld %9.3f %12.3f %12s\n", "gearsph, run in this process", n_ours,
                static_cast<long long>(ours.steps_done), ours.wall_s, 1e-6 * ours_rate,
                perr(a.value("period_error", json())).c_str());
    std::printf("%-34s %9zu %8lld %9.3f %12.3f %12s\n",
                user_ok ? "gearsph run, default output" : "gearsph run (FAILED)", n_ours,
                static_cast<long long>(planned_steps), user_s, 1e-6 * user_rate, "");
    const std::filesystem::path script = find_pysph_script(script_opt);
    if (no_pysph) {
      row["pysph"] = {{"skipped", "--no-pysph"}};
    } else if (script.empty()) {
      row["pysph"] = {{"skipped", "bench/pysph_plate.py not found (give --pysph-script)"}};
      std::printf("PySPH: bench/pysph_plate.py not found (give --pysph-script)\n");
    } else {
      const int every = quick ? 1000000 : 100;  // tip samples for the period
      const PysphResult py =
          run_pysph(python, script, std::filesystem::path(out) / "pysph", vf, end_s, every);
      if (!py.ok) {
        row["pysph"] = {{"error", py.message}};
        std::printf("PySPH: %s\n", py.message.c_str());
      } else {
        const json& p = py.report;
        const double n = p.at("particles").get<double>(), steps = p.at("steps").get<double>();
        const double run_s = p.at("run_s").get<double>();
        const double rate = n * steps / run_s;
        std::printf("%-34s %9.0f %8.0f %9.3f %12.3f %12s\n", "PySPH, its time loop", n, steps,
                    run_s, 1e-6 * rate, perr(p.value("period_error", json())).c_str());
        std::printf(
            "ratio to PySPH (particle-steps/s): bare %.1f, in this process %.1f, "
            "end to end %.1f   (target >= 30 end to end)\n",
            bare.particle_steps_per_s() / rate, ours_rate / rate, user_rate / rate);
        row["pysph"] = p;
        row["pysph"]["particle_steps_per_s"] = rate;
        row["pysph"]["process_cpu_s"] = py.cpu_s;
        row["ratio"] = ours_rate / rate;
        row["ratio_bare"] = bare.particle_steps_per_s() / rate;
        row["ratio_end_to_end"] = user_ok ? json(user_rate / rate) : json();
      }
    }
    report["pysph_plate"] = row;
    std::printf("\n");
  }

  // 3. Cost per particle-step and memory per particle, 1e3 .. 1e6 particles:
  // the plate with the spacing for each count (N ~ 0.005 m^2 / dx^2).
  {
    std::printf("3. Scaling (plate, 2 threads, bare steps)\n");
    std::printf("%9s %10s %7s %10s %13s %12s %12s %12s\n", "target", "particles", "steps", "wall_s",
                "wall ns/p-st", "cpu ns/p-st", "rss B/part", "peak B/part");
    json rows = json::array();
    for (double target : {1e3, 1e4, 1e5, 1e6}) {
      if (target > max_particles) break;
      const double dx = std::sqrt(0.005 / target);
      // About 5e6 particle-steps each (--quick: 1e6), at least three steps.
      const std::int64_t steps =
          std::max<std::int64_t>(3, std::llround((quick ? 1e6 : 5e6) / target));
      const Timing x = time_steps(plate_job(dx), 2, steps);
      std::printf("%9.0e %10zu %7lld %10.3f %13.1f %12.1f %12.0f %12.0f\n", target, x.particles,
                  static_cast<long long>(steps), x.wall_s, x.ns_per_particle_step(),
                  x.cpu_ns_per_particle_step(), x.rss_per_particle, x.peak_per_particle);
      rows.push_back({{"target", target},
                      {"particles", x.particles},
                      {"pairs_per_step", x.pairs},
                      {"steps", steps},
                      {"wall_s", x.wall_s},
                      {"cpu_s", x.cpu_s},
                      {"ns_per_particle_step", x.ns_per_particle_step()},
                      {"cpu_ns_per_particle_step", x.cpu_ns_per_particle_step()},
                      {"rss_bytes_per_particle", x.rss_per_particle},
                      {"peak_bytes_per_particle", x.peak_per_particle}});
    }
    report["scaling"] = rows;
    // Per particle added between the two largest cases: what a particle
    // costs without the fixed part (libraries, threads' stacks, the heap's
    // first megabytes), which dominates the per-particle figure at 1e3-1e4.
    if (rows.size() >= 2) {
      const json& a = rows[rows.size() - 2];
      const json& b = rows.back();
      const double na = a["particles"].get<double>(), nb = b["particles"].get<double>();
      auto added = [&](const char* key) {
        return (b[key].get<double>() * nb - a[key].get<double>() * na) / (nb - na);
      };
      const double rss = added("rss_bytes_per_particle");
      const double peak = added("peak_bytes_per_particle");
      std::printf("   per particle added from %.0e to %.0e: rss %.0f B, peak %.0f B\n",
                  a["target"].get<double>(), b["target"].get<double>(), rss, peak);
      report["scaling_added_particle"] = {
          {"from", a["target"]}, {"to", b["target"]}, {"rss_bytes", rss}, {"peak_bytes", peak}};
    }
    std::printf("\n");
  }

  // 4. The paper's full case (1e6 steps of 4e-8 s), as `gearsph run` does it.
  if (!skip_full) {
    // --quick: the first 2 % of the steps, scaled. The scene is built for the
    // full end time (it models the teeth that engage in it), so the step
    // count is cut after preparing, not the end time.
    const double fraction = quick ? 0.02 : 1.0;
    PreparedJob pj = prepare_job(gear_job(), 2);
    pj.steps = std::llround(fraction * double(pj.steps));
    const double c0 = cpu_seconds();
    const RunResult r = run_job(pj);
    const double cpu_s = cpu_seconds() - c0;
    const double full_s = r.wall_s / fraction;
    std::printf(
        "4. Paper's gear case: %zu particles, %lld steps, 2 threads: %.1f s wall, %.1f s "
        "CPU%s  (target < 120 s, stretch < 60 s)\n",
        pj.scene.sim.particles.n, static_cast<long long>(r.steps_done), r.wall_s, cpu_s,
        quick ? fmt(" -> full case %.0f s (scaled from 2 %%)", full_s).c_str() : "");
    report["full_case"] = {{"particles", pj.scene.sim.particles.n},
                           {"steps", r.steps_done},
                           {"wall_s", r.wall_s},
                           {"fraction_run", fraction},
                           {"full_case_wall_s", full_s},
                           {"cpu_s", cpu_s},
                           {"status", r.status}};
  }
  // 5. A study through the service, as design automation submits one: the
  // paper's case N times (--quick: its first 2 ms), at the server's defaults.
#ifdef GEARSPH_WITH_SERVICE
  if (!skip_study && study_jobs > 0) {
    const double end_s = quick ? 0.002 : 0.04;
    try {
      const json st = study_throughput(std::filesystem::path(out) / "study", study_jobs, end_s);
      std::printf(
          "\n5. A study of %d paper's cases (%g s each) through gearsph serve on %d cores: "
          "%.1f s, %.2f job-times of %.1f s (ideal %.1f), %.0f jobs per hour (%d of %d "
          "jobs on one thread)\n",
          study_jobs, end_s, st.at("cores").get<int>(), st.at("study_wall_s").get<double>(),
          st.at("job_times").get<double>(), st.at("mean_job_time_s").get<double>(),
          st.at("ideal_job_times").get<double>(), st.at("jobs_per_hour").get<double>(),
          st.at("jobs_on_one_thread").get<int>(), study_jobs);
      report["study"] = st;
    } catch (const std::exception& e) {
      std::printf("\n5. The study through gearsph serve failed: %s\n", e.what());
      report["study"] = {{"error", e.what()}};
    }
  }
#endif
  write_file_atomic(std::filesystem::path(out) / "bench.json", report.dump(2) + "\n");
  std::printf("\nreport: %s/bench.json\n", out.c_str());
  return 0;
}

// ---------------------------------------------------------------- pareto

struct Setting {
  std::string kernel;
  double h_over_dx = 0;  // 0: the kernel's default
  int across = 10;       // particles across the plate thickness (H/dx), or the Hertz a/dx
  double cfl = 0;        // 0: the default step (80 % of the measured limit)
  std::string formulation = "total_lagrangian";
  std::string label = {};  // as printed and charted
  double spacing_mm = 0;   // the gear sweep's spacing
};

std::string plate_label(const Setting& s) {
  std::string l = s.kernel + " H/dx=" + std::to_string(s.across);
  if (s.h_over_dx > 0) l += " h/dx=" + fmt("%.2g", s.h_over_dx);
  if (s.cfl > 0) l += " cfl=" + fmt("%.2g", s.cfl);
  l += s.formulation == "total_lagrangian" ? " TL" : " UL";
  return l;
}

// Indices of the points no other point beats in both cost and error.
std::vector<bool> pareto_front(const std::vector<double>& cost, const std::vector<double>& err) {
  std::vector<bool> front(cost.size(), false);
  for (std::size_t i = 0; i < cost.size(); ++i) {
    if (!std::isfinite(err[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < cost.size() && !dominated; ++j) {
      if (j == i || !std::isfinite(err[j])) continue;
      dominated = cost[j] <= cost[i] && err[j] <= err[i] && (cost[j] < cost[i] || err[j] < err[i]);
    }
    front[i] = !dominated;
  }
  return front;
}

#ifdef GEARSPH_WITH_RENDER
// Error against cost on log-log axes: one marker series per kernel, the
// Pareto front as a line.
void pareto_chart(const std::filesystem::path& path, const std::string& title,
                  const std::string& error_name, const std::vector<Setting>& set,
                  const std::vector<double>& cost, const std::vector<double>& err,
                  const std::vector<bool>& front) {
  render::Plot plot;
  plot.title = title;
  plot.x_label = "log10 CPU time [s]";
  plot.y_label = "log10 |" + error_name + "|";
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (std::size_t i = 0; i < set.size(); ++i) {
    if (!std::isfinite(err[i]) || err[i] <= 0) continue;
    x0 = std::min(x0, std::log10(cost[i]));
    x1 = std::max(x1, std::log10(cost[i]));
    y0 = std::min(y0, std::log10(err[i]));
    y1 = std::max(y1, std::log10(err[i]));
  }
  if (x0 > x1) return;
  const double mx = 0.08 * std::max(x1 - x0, 0.1), my = 0.08 * std::max(y1 - y0, 0.1);
  plot.x_range = render::Range{x0 - mx, x1 + mx};
  plot.y_range = render::Range{y0 - my, y1 + my};
  const double dxm = 0.25 * mx, dym = 0.25 * my;  // marker half size
  const char* kernels[] = {"seed_quartic", "cubic_spline", "quintic_spline", "wendland_c2"};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const char* k : kernels) {
    for (const char* form : {"total_lagrangian", "updated_lagrangian"}) {
      render::Series s;
      s.name = std::string(k) + (std::string(form) == "total_lagrangian" ? " TL (x)" : " UL (+)");
      const bool tl = std::string(form) == "total_lagrangian";
      for (std::size_t i = 0; i < set.size(); ++i) {
        if (set[i].kernel != k || set[i].formulation != form) continue;
        if (!std::isfinite(err[i]) || err[i] <= 0) continue;
        const double x = std::log10(cost[i]), y = std::log10(err[i]);
        // TL: a cross; UL: a plus.
        if (tl) {
          s.x.insert(s.x.end(), {x - dxm, x + dxm, nan, x - dxm, x + dxm, nan});
          s.y.insert(s.y.end(), {y - dym, y + dym, nan, y + dym, y - dym, nan});
        } else {
          s.x.insert(s.x.end(), {x - dxm, x + dxm, nan, x, x, nan});
          s.y.insert(s.y.end(), {y, y, nan, y - dym, y + dym, nan});
        }
      }
      if (!s.x.empty()) plot.series.push_back(s);
    }
  }
  render::Series f;
  f.name = "Pareto front";
  f.colour = render::Rgb8{0, 0, 0};
  std::vector<std::pair<double, double>> pts;
  for (std::size_t i = 0; i < set.size(); ++i)
    if (front[i] && err[i] > 0) pts.emplace_back(std::log10(cost[i]), std::log10(err[i]));
  std::sort(pts.begin(), pts.end());
  for (std::size_t k = 0; k < pts.size(); ++k) {
    // A staircase: each front point holds its error until the next, cheaper
    // to more expensive.
    f.x.push_back(pts[k].first);
    f.y.push_back(pts[k].second);
    if (k + 1 < pts.size()) {
      f.x.push_back(pts[k + 1].first);
      f.y.push_back(pts[k].second);
    }
  }
  plot.series.push_back(f);
  render::write_png(path, render::render_plot_png(plot));
}
#endif

// The rows of a sweep (written as they finish), its Pareto front
// (pareto_NAME_front.csv), the chart (pareto_NAME.png) and the front printed.
void report_sweep(const std::filesystem::path& out, const std::string& name,
                  [[maybe_unused]] const std::string& title, const std::string& error_name,
                  const std::vector<Setting>& set, const std::vector<double>& cost,
                  const std::vector<double>& err, std::ofstream& csv,
                  const std::vector<std::string>& csv_rows) {
  const std::vector<bool> front = pareto_front(cost, err);
  std::ofstream fcsv(out / ("pareto_" + name + "_front.csv"));
  fcsv << "setting,cpu_s,abs_error\n";
  for (std::size_t i = 0; i < set.size(); ++i) {
    csv << csv_rows[i] << '\n';
    if (front[i]) fcsv << set[i].label << ',' << cost[i] << ',' << err[i] << '\n';
  }
  csv.flush();
  const std::filesystem::path png = out / ("pareto_" + name + ".png");
#ifdef GEARSPH_WITH_RENDER
  pareto_chart(png, title, error_name, set, cost, err, front);
  std::printf("chart: %s\n", png.c_str());
#else
  std::printf("(built without the renderer: no PNG chart)\n");
#endif
  std::printf("Pareto front, %s (cheapest first):\n", error_name.c_str());
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < set.size(); ++i)
    if (front[i]) idx.push_back(i);
  std::sort(idx.begin(), idx.end(), [&](auto a, auto b) { return cost[a] < cost[b]; });
  for (std::size_t i : idx)
    std::printf("  %-52s cpu %8.2f s  |error| %.3g%%\n", set[i].label.c_str(), cost[i],
                100 * err[i]);
}

// One run of a sweep: CPU time and the summary (empty when refused).
struct SweepRun {
  double cpu = 0, wall = 0, dt = 0;
  std::size_t particles = 0;
  std::int64_t steps = 0;
  std::string status;
  json summary;
};

SweepRun run_for_sweep(const json& job, int threads) {
  SweepRun r;
  try {
    PreparedJob pj = prepare_job(job, threads);
    r.particles = pj.scene.sim.particles.n;
    r.dt = pj.scene.sim.dt;
    const double c0 = cpu_seconds();
    const RunResult rr = run_job(pj);
    r.cpu = cpu_seconds() - c0;
    r.wall = rr.wall_s;
    r.steps = rr.steps_done;
    r.status = rr.status;
    r.summary = rr.summary;
  } catch (const std::exception& e) {
    r.status = std::string("refused: ") + e.what();
    for (char& c : r.status)
      if (c == ',' || c == '\n') c = ';';
  }
  return r;
}

// Hertz line contact (validation.md 6): peak-pressure error against cost,
// over kernel and a/dx (the contact half-width in spacings), TL.
void hertz_sweep(const std::filesystem::path& out, bool quick, int threads) {
  const char* kernels[] = {"seed_quartic", "cubic_spline", "quintic_spline", "wendland_c2"};
  const double a = 4.8138e-4;  // the scene's half-width at its default load [m]
  const std::vector<int> across = quick ? std::vector<int>{3, 4} : std::vector<int>{3, 4, 6};
  std::vector<Setting> set;
  for (const char* k : kernels)
    for (int n : across) {
      Setting s{k, 0, n, 0, "total_lagrangian"};
      s.label = std::string(k) + " a/dx=" + std::to_string(n);
      set.push_back(s);
    }
  std::vector<double> cost(set.size(), 0.0), err(set.size(), std::nan(""));
  std::ofstream csv(out / "pareto_hertz.csv");
  csv << "kernel,a_over_dx,particles,steps,wall_s,cpu_s,peak_pressure_Pa,reference_Pa,"
         "p0_error,half_width_error,status\n";
  std::vector<std::string> rows;
  std::printf("\n%-52s %9s %8s %9s %9s %11s\n", "Hertz setting", "particles", "steps", "wall_s",
              "cpu_s", "p0_err");
  for (std::size_t i = 0; i < set.size(); ++i) {
    const json job = {
        {"name", "pareto-hertz"},
        {"scene",
         {{"type", "hertz"},
          {"cap_height_over_a", 6.0},
          {"block_half_width_over_a", 6.0},
          {"block_depth_over_a", 6.0}}},
        {"discretization", {{"spacing_m", a / set[i].across}, {"kernel", set[i].kernel}}},
        {"output", {{"frames", 0}}}};
    const SweepRun r = run_for_sweep(job, threads);
    double p0 = std::nan(""), ref = std::nan(""), aerr = std::nan("");
    if (r.summary.contains("analysis") && r.summary["analysis"].contains("peak_pressure_Pa")) {
      const json& an = r.summary.at("analysis");
      p0 = an.at("peak_pressure_Pa").get<double>();
      ref = an.at("reference_peak_pressure_Pa").get<double>();
      aerr =
          an.at("half_width_m").get<double>() / an.at("reference_half_width_m").get<double>() - 1;
      err[i] = std::abs(p0 / ref - 1.0);
    }
    cost[i] = r.cpu;
    std::printf(
        "%-52s %9zu %8lld %9.2f %9.2f %11s\n", set[i].label.c_str(), r.particles,
        static_cast<long long>(r.steps), r.wall, r.cpu,
        std::isfinite(err[i]) ? fmt("%+.2f%%", 100 * (p0 / ref - 1)).c_str() : r.status.c_str());
    std::fflush(stdout);
    std::ostringstream line;
    line << set[i].kernel << ',' << set[i].across << ',' << r.particles << ',' << r.steps << ','
         << r.wall << ',' << r.cpu << ',' << p0 << ',' << ref << ',' << (p0 / ref - 1) << ','
         << aerr << ',' << r.status;
    rows.push_back(line.str());
  }
  report_sweep(out, "hertz", "Hertz line contact: peak-pressure error against CPU time", "p0 error",
               set, cost, err, csv, rows);
}

// The quasi-static gear (validation.md 7, 1 kN): tooth 0's nominal root
// bending stress against the finest run's, over kernel and spacing.
void gear_sweep(const std::filesystem::path& out, bool quick, int threads) {
  const char* kernels[] = {"seed_quartic", "cubic_spline", "quintic_spline", "wendland_c2"};
  const std::vector<double> spacings_mm =
      quick ? std::vector<double>{1.0} : std::vector<double>{1.0, 0.5};
  const double finest_mm = quick ? 0.5 : 0.25;
  auto job = [](const std::string& kernel, double dx_mm) {
    return json{{"name", "pareto-gear"},
                {"scene",
                 {{"type", "rack_pinion"},
                  {"quasi_static", true},
                  {"pinion", {{"omega_rad_s", 0.0}}},
                  {"rack", {{"velocity_m_s", 0.0}, {"load_N", 1000.0}}}}},
                {"discretization", {{"spacing_mm", dx_mm}, {"kernel", kernel}}},
                {"output", {{"frames", 0}}}};
  };
  auto bending = [](const SweepRun& r) {
    return r.summary.contains(json::json_pointer("/analysis/static_check"))
               ? r.summary.at(json::json_pointer("/analysis/static_check"))
                     .at("nominal_bending_stress_Pa")
                     .get<double>()
               : std::nan("");
  };
  std::printf("\nGear reference: seed_quartic at %.2g mm ...\n", finest_mm);
  std::fflush(stdout);
  const SweepRun finest = run_for_sweep(job("seed_quartic", finest_mm), threads);
  const double reference = bending(finest);
  std::printf("  %.4g MPa (%zu particles, cpu %.1f s)\n", 1e-6 * reference, finest.particles,
              finest.cpu);
  std::vector<Setting> set;
  for (const char* k : kernels)
    for (double mm : spacings_mm) {
      Setting s{k, 0, 0, 0, "total_lagrangian"};
      s.label = std::string(k) + " dx=" + fmt("%.2g", mm) + " mm";
      s.spacing_mm = mm;
      set.push_back(s);
    }
  std::vector<double> cost(set.size(), 0.0), err(set.size(), std::nan(""));
  std::ofstream csv(out / "pareto_gear.csv");
  csv << "kernel,spacing_mm,particles,steps,wall_s,cpu_s,root_bending_Pa,reference_Pa,"
         "reference_spacing_mm,error,status\n";
  std::vector<std::string> rows;
  std::printf("%-52s %9s %8s %9s %9s %11s\n", "gear setting", "particles", "steps", "wall_s",
              "cpu_s", "root_err");
  for (std::size_t i = 0; i < set.size(); ++i) {
    const SweepRun r = run_for_sweep(job(set[i].kernel, set[i].spacing_mm), threads);
    const double sigma = bending(r);
    const double e = sigma / reference - 1.0;
    err[i] = std::abs(e);
    cost[i] = r.cpu;
    std::printf("%-52s %9zu %8lld %9.2f %9.2f %11s\n", set[i].label.c_str(), r.particles,
                static_cast<long long>(r.steps), r.wall, r.cpu,
                std::isfinite(e) ? fmt("%+.2f%%", 100 * e).c_str() : r.status.c_str());
    std::fflush(stdout);
    std::ostringstream line;
    line << set[i].kernel << ',' << set[i].spacing_mm << ',' << r.particles << ',' << r.steps << ','
         << r.wall << ',' << r.cpu << ',' << sigma << ',' << reference << ',' << finest_mm << ','
         << e << ',' << r.status;
    rows.push_back(line.str());
  }
  report_sweep(out, "gear", "Static gear: root bending error (vs the finest run) against CPU time",
               "root bending error", set, cost, err, csv, rows);
}

int pareto_main(Args& args) {
  const bool quick = args.flag("quick");
  const auto out_opt = args.option("out");
  const int threads = args.integer("threads", 1);
  const std::string cases = args.option("cases").value_or("plate,hertz,gear");
  args.positional();
  if (!out_opt) {
    throw std::invalid_argument(
        "usage: gearsph bench pareto --out DIR [--quick] [--cases plate,hertz,gear]");
  }
  const std::filesystem::path out = *out_opt;
  std::filesystem::create_directories(out);
  auto wanted = [&cases](const char* c) { return cases.find(c) != std::string::npos; };
  if (wanted("hertz")) hertz_sweep(out, quick, threads);
  if (wanted("gear")) gear_sweep(out, quick, threads);
  if (!wanted("plate")) return 0;

  const char* kernels[] = {"seed_quartic", "cubic_spline", "quintic_spline", "wendland_c2"};
  std::vector<Setting> set;
  // The kernel x spacing x formulation grid at default h/dx and step ...
  const std::vector<int> across = quick ? std::vector<int>{5, 10} : std::vector<int>{5, 10, 20};
  // UL costs ~10x TL per step (kernel sums on the moving configuration,
  // neighbour rebuilds): --quick runs it at the coarsest spacing only.
  for (const char* k : kernels)
    for (int a : across)
      for (const char* f : {"total_lagrangian", "updated_lagrangian"})
        if (!(quick && a > across.front() && std::string(f) == "updated_lagrangian"))
          set.push_back({k, 0, a, 0, f});
  // ... and one factor at a time around H/dx = 10, TL: a wider and a
  // narrower kernel, a small and a large Courant number.
  for (const char* k : kernels) {
    const bool support3 = std::string(k) == "seed_quartic" || std::string(k) == "quintic_spline";
    set.push_back({k, support3 ? 1.3 : 1.2, 10, 0, "total_lagrangian"});
    if (!quick) set.push_back({k, support3 ? 0.8 : 2.0, 10, 0, "total_lagrangian"});
  }
  for (const char* k : {"seed_quartic", "wendland_c2"}) {
    set.push_back({k, 0, 10, 0.1, "total_lagrangian"});
    set.push_back({k, 0, 10, 0.4, "total_lagrangian"});
  }

  for (Setting& s : set) s.label = plate_label(s);
  std::vector<double> cost(set.size(), 0.0), err(set.size(), std::nan(""));
  std::ofstream csv(out / "pareto_plate.csv");
  csv << "kernel,h_over_dx,H_over_dx,formulation,cfl,dt_s,particles,steps,wall_s,cpu_s,"
         "period_s,period_error,amplitude_decay_2_periods,status\n";
  std::printf("%-52s %9s %8s %9s %9s %11s\n", "setting", "particles", "steps", "wall_s", "cpu_s",
              "period_err");
  std::vector<std::string> csv_rows;
  for (std::size_t i = 0; i < set.size(); ++i) {
    const Setting& s = set[i];
    json job = plate_job(0.02 / s.across);
    job["discretization"]["kernel"] = s.kernel;
    if (s.h_over_dx > 0) job["discretization"]["h_over_dx"] = s.h_over_dx;
    job["method"] = {{"formulation", s.formulation}};
    // 1.7 reference periods: three zero crossings even with a 10 % long period.
    job["time"] = {{"end_s", 1.7 * 0.2540606}};
    if (s.cfl > 0) job["time"]["cfl"] = s.cfl;
    job["output"]["history_points"] = 2000;
    std::string status;
    double wall = 0, cpu = 0, dt = 0, period = std::nan(""), perr = std::nan(""), decay = 0;
    std::size_t n = 0;
    std::int64_t steps = 0;
    try {
      PreparedJob pj = prepare_job(job, threads);
      n = pj.scene.sim.particles.n;
      dt = pj.scene.sim.dt;
      const double c0 = cpu_seconds();
      const RunResult r = run_job(pj);
      cpu = cpu_seconds() - c0;
      wall = r.wall_s;
      steps = r.steps_done;
      status = r.status;
      const json& a = r.summary.at("analysis");
      if (a.value("period_s", json()).is_number()) {
        period = a.at("period_s").get<double>();
        perr = a.at("period_error").get<double>();
      }
      const json d = a.value("amplitude_decay_2_periods", json());
      decay = d.is_number() ? d.get<double>() : std::nan("");
    } catch (const std::exception& e) {
      status = std::string("refused: ") + e.what();
      for (char& c : status)
        if (c == ',' || c == '\n') c = ';';
    }
    cost[i] = cpu;
    err[i] = std::abs(perr);
    std::printf("%-52s %9zu %8lld %9.2f %9.2f %11s\n", s.label.c_str(), n,
                static_cast<long long>(steps), wall, cpu,
                std::isfinite(perr) ? fmt("%+.2f%%", 100 * perr).c_str() : status.c_str());
    std::fflush(stdout);
    std::ostringstream line;
    line << s.kernel << ',' << (s.h_over_dx > 0 ? fmt("%.3g", s.h_over_dx) : "default") << ','
         << s.across << ',' << s.formulation << ',' << (s.cfl > 0 ? fmt("%.3g", s.cfl) : "default")
         << ',' << dt << ',' << n << ',' << steps << ',' << wall << ',' << cpu << ',' << period
         << ',' << perr << ',' << decay << ',' << status;
    csv_rows.push_back(line.str());
  }
  report_sweep(out, "plate", "Oscillating plate: period error against CPU time", "period error",
               set, cost, err, csv, csv_rows);
  return 0;
}

}  // namespace

// `gearsph bench [options]` or `gearsph bench pareto [options]`.
int cmd_bench(int argc, char** argv) {
  // The wait policy main() chose, or the caller's (docs/speed-accuracy.md).
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  const char* spin = std::getenv("GOMP_SPINCOUNT");
  std::printf("OpenMP wait: OMP_WAIT_POLICY=%s GOMP_SPINCOUNT=%s\n", policy ? policy : "(unset)",
              spin ? spin : "(unset)");
  if (argc > 2 && std::string(argv[2]) == "pareto") {
    Args args(argc, argv, 3);
    return pareto_main(args);
  }
  Args args(argc, argv, 2);
  return bench_main(args);
}

}  // namespace gearsph::cli
