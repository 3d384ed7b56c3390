// gearsph bench: the speed numbers of issue 7 side by side in one run
// (throughput of the plate and the gear case at 1 and 2 threads, PySPH on
// the same plate, cost per particle-step from 1e3 to 1e6 particles, memory
// per particle, the seed paper's full case, a study through the service); each
// section is a function below. `gearsph bench pareto` (error against cost)
// runs the sweeps of bench_pareto.hpp; the timing itself is
// bench_measure.hpp.
// docs/speed-accuracy.md explains every number and records measured ones.
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
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/gearsph/bench_measure.hpp"
#include "apps/gearsph/bench_pareto.hpp"
#include "apps/gearsph/cli.hpp"
#include "solver/job/job.hpp"
#include "solver/run/execute.hpp"
#include "solver/run/runner.hpp"
#ifdef GEARSPH_WITH_SERVICE
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>

#include <thread>

#include "server/http_client.hpp"
#endif

namespace gearsph::cli {

namespace {

using namespace bench;

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

// A study of `jobs` copies of the seed paper's case (the first `end_s` of it):
// the study's record once it has ended.
json run_study(server::HttpClient& c, int jobs, double end_s) {
  json base = {{"scene", {{"type", "rack_pinion"}}}, {"time", {{"end_s", end_s}}}};
  json names = json::array();
  for (int k = 1; k <= jobs; ++k) names.push_back("paper-" + std::to_string(k));
  const json study = {
      {"name", "bench"}, {"base", base}, {"axes", {{{"pointer", "/name"}, {"values", names}}}}};
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
  return done;
}

// The study's completed jobs: a job's time from claimed to finished (set-up,
// run and results) as the store records it, the run's own wall time beside
// it, and how many ran on one thread.
struct StudyJobs {
  double job_time_s = 0.0, run_wall_s = 0.0;  // sums
  int one_thread = 0, completed = 0;
};

StudyJobs study_jobs(server::HttpClient& c, const json& done) {
  StudyJobs s;
  for (const json& j : done.at("jobs")) {
    const std::string job_id = j.at("jobID");
    const server::ClientResponse summary = c.get("/jobs/" + job_id + "/files/summary.json");
    const json record = c.get("/jobs/" + job_id).json();
    if (summary.status != 200 || !record.at("finished").is_string()) continue;
    const json run = summary.json();
    ++s.completed;
    s.run_wall_s += run.at("wall_s").get<double>();
    s.job_time_s += utc_seconds(record.at("finished")) - utc_seconds(record.at("started"));
    s.one_thread += run.at("threads").get<int>() == 1 ? 1 : 0;
  }
  return s;
}

// A study of `jobs` copies of the seed paper's case (the first `end_s` of it)
// submitted at once to `gearsph serve` at its defaults: how long the
// study takes against one job's time, and jobs per hour.
json study_throughput(const std::filesystem::path& dir, int jobs, double end_s) {
  ServeChild serve(dir);
  server::HttpClient c(serve.host(), serve.port(), std::chrono::seconds(60));
  const auto t0 = Clock::now();
  const json done = run_study(c, jobs, end_s);
  const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  const StudyJobs s = study_jobs(c, done);
  const int ok = s.completed;
  const json health = c.get("/health").json();
  const double mean = s.job_time_s / std::max(ok, 1);
  const int cores = health.value("core_budget", 0) > 0 ? health.at("core_budget").get<int>()
                                                       : health.at("workers").get<int>();
  return {{"jobs", jobs},
          {"end_s", end_s},
          {"status", done.at("status")},
          {"completed", ok},
          {"cores", cores},
          {"core_budget", health.value("core_budget", 0)},
          {"jobs_on_one_thread", s.one_thread},
          {"study_wall_s", wall},
          {"mean_job_time_s", mean},
          {"mean_run_wall_s", s.run_wall_s / std::max(ok, 1)},
          {"job_times", wall / mean},
          {"ideal_job_times", double(jobs) / cores},
          {"jobs_per_hour", 3600.0 * jobs / wall}};
}
#endif

// ---------------------------------------------------------------- bench

struct BenchOptions {
  bool quick = false, no_pysph = false, skip_full = false, skip_study = false;
  int study_jobs = 16, repeats = 3;
  std::string out, python;
  std::optional<std::string> pysph_script;
  double max_particles = 1e6;
};

BenchOptions read_options(Args& args) {
  BenchOptions o;
  o.quick = args.flag("quick");
  o.no_pysph = args.flag("no-pysph");
  o.skip_full = args.flag("skip-full");
  o.skip_study = args.flag("skip-study");
  o.study_jobs = args.integer("study-jobs", 16);
  o.out = args.option("out").value_or("bench");
  o.python = args.option("python").value_or("/usr/bin/python3");
  o.pysph_script = args.option("pysph-script");
  o.repeats = args.integer("repeats", o.quick ? 2 : 3);
  o.max_particles = std::stod(args.option("max-particles").value_or("1e6"));
  args.positional();
  return o;
}

// The report's first fields, and the load average printed: on a shared
// machine the ratios are what to read.
json start_report(bool quick) {
  json report;
  report["quick"] = quick;
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) == 3) report["load_average_1min"] = load[0];
  std::printf("gearsph bench%s: load average %.2f (on a shared machine read the ratios)\n\n",
              quick ? " --quick" : "", load[0]);
  return report;
}

// ------------------------------------------ 1. throughput at 1 and 2 threads

struct ThroughputCase {
  std::string name;
  json job;
  std::int64_t steps;
};

constexpr std::array<int, 2> kThreadCounts = {1, 2};

// The fine plate (0.3 mm, ~56,000 particles) shows the threads where a
// step is long enough that barriers do not dominate.
std::vector<ThroughputCase> throughput_cases(bool quick) {
  return {{"plate", plate_job(0.002), quick ? 1000 : 4000},
          {"gear", gear_job(), quick ? 2000 : 10000},
          {"plate-fine", plate_job(0.0003), quick ? 40 : 150}};
}

// Every case at every thread count, interleaved, the best of `repeats`.
std::vector<std::array<Timing, 2>> best_timings(const std::vector<ThroughputCase>& cases,
                                                int repeats) {
  std::vector<std::array<Timing, 2>> best(cases.size());
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t c = 0; c < cases.size(); ++c) {
      for (std::size_t t = 0; t < kThreadCounts.size(); ++t) {
        const Timing x = time_steps(cases[c].job, kThreadCounts[t], cases[c].steps);
        if (r == 0 || x.wall_s < best[c][t].wall_s) best[c][t] = x;
      }
    }
  }
  return best;
}

// One line of the table, and its row of the report.
json throughput_row(const std::string& name, int threads, const Timing& x, double speedup) {
  std::printf("%-10s %7d %9zu %7zu %8lld %8.3f %8.3f %11.3f %10.2f %8.2f %12.1f\n", name.c_str(),
              threads, x.particles, x.pairs, static_cast<long long>(x.steps), x.wall_s, x.cpu_s,
              1e-6 * x.particle_steps_per_s(), 1e-6 * x.pairs_per_s(), speedup,
              x.cpu_ns_per_particle_step());
  return {{"case", name},
          {"threads", threads},
          {"particles", x.particles},
          {"pairs_per_step", x.pairs},
          {"steps", x.steps},
          {"dt_s", x.dt},
          {"wall_s", x.wall_s},
          {"cpu_s", x.cpu_s},
          {"particle_steps_per_s", x.particle_steps_per_s()},
          {"pair_interactions_per_s", x.pairs_per_s()},
          {"speedup_vs_1_thread", speedup},
          {"cpu_ns_per_particle_step", x.cpu_ns_per_particle_step()}};
}

// Where the step's time goes, pass by pass (as Box2D times its stages), for
// each case at 1 and 2 threads: microseconds a step and share.
void print_passes(const std::vector<ThroughputCase>& cases,
                  const std::vector<std::array<Timing, 2>>& best, json& report) {
  std::printf("1b. The step's passes (us a step, share; one step in %lld timed)\n",
              static_cast<long long>(PassTimes::kTimedEvery));
  json all = json::object();
  for (std::size_t c = 0; c < cases.size(); ++c) {
    std::printf("%-10s %-28s %10s %7s %10s %7s\n", cases[c].name.c_str(), "pass", "1 thread", "",
                "2 threads", "");
    const json& one = best[c][0].passes.at("passes");
    const json& two = best[c][1].passes.at("passes");
    for (const json& a : one) {
      json b = json::object();
      for (const json& x : two) {
        if (x.at("name") == a.at("name")) b = x;
      }
      const double steps1 = double(best[c][0].steps), steps2 = double(best[c][1].steps);
      const double us2 = b.empty() ? 0.0 : 1e6 * b.at("seconds").get<double>() / steps2;
      const double share2 = b.empty() ? 0.0 : 100.0 * b.at("share").get<double>();
      std::printf("%-10s %-28s %10.2f %6.1f%% %10.2f %6.1f%%\n", "",
                  a.at("name").get<std::string>().c_str(),
                  1e6 * a.at("seconds").get<double>() / steps1, 100.0 * a.at("share").get<double>(),
                  us2, share2);
    }
    all[cases[c].name] = {{"1_thread", best[c][0].passes}, {"2_threads", best[c][1].passes}};
  }
  report["passes"] = all;
  std::printf("\n");
}

void bench_throughput(const BenchOptions& o, json& report) {
  const std::vector<ThroughputCase> cases = throughput_cases(o.quick);
  const std::vector<std::array<Timing, 2>> best = best_timings(cases, o.repeats);
  std::printf("1. Throughput (bare time steps, best of %d)\n", o.repeats);
  // cpu ns/p-st: CPU time of all threads per particle-step; on a quiet
  // machine wall * threads ~ CPU, on a loaded one wall >> CPU / threads.
  std::printf("%-10s %7s %9s %7s %8s %8s %8s %11s %10s %8s %12s\n", "case", "threads", "particles",
              "pairs", "steps", "wall_s", "cpu_s", "Mpart-st/s", "Mpairs/s", "speed-up",
              "cpu ns/p-st");
  json rows = json::array();
  for (std::size_t c = 0; c < cases.size(); ++c) {
    for (std::size_t t = 0; t < kThreadCounts.size(); ++t) {
      const double speedup = best[c][0].wall_s / best[c][t].wall_s;
      rows.push_back(throughput_row(cases[c].name, kThreadCounts[t], best[c][t], speedup));
    }
  }
  report["throughput"] = rows;
  std::printf("\n");
  print_passes(cases, best, report);
}

// ------------------------------------------ 2. the oscillating plate against PySPH

// PySPH's settings for its plate: dx 2 mm, cubic spline, h 1.3 dx, dt 1e-5 s,
// Vf 0.01, one thread. 2000 steps (issue 30's case); the full bench runs
// past one period (three zero crossings with a 10 % long period) for the
// period error.
struct PysphSettings {
  double dt = 1e-5, vf = 0.01, end_s = 0.02;
};

PysphSettings pysph_settings(bool quick) {
  PysphSettings s;
  s.end_s = quick ? 0.02 : 0.32;
  return s;
}

json pysph_plate_job(const PysphSettings& s, bool quick) {
  json job = plate_job(0.002, s.vf);
  job["discretization"]["kernel"] = "cubic_spline";
  job["discretization"]["h_over_dx"] = 1.3;
  job["time"] = {{"dt_s", s.dt}, {"end_s", s.end_s}};
  job["output"]["history_points"] = quick ? 100 : 3200;
  return job;
}

// `gearsph run` of a job as a user runs it, the whole process timed, best
// of `repeats` (stops at the first failure).
struct ProcessRun {
  std::string command;
  bool ok = true;
  double wall_s = std::numeric_limits<double>::infinity();
};

// `gearsph run` of each job in turn, `repeats` rounds (the two alternate,
// so a slow spell of the machine falls on both), best of each.
std::vector<ProcessRun> time_gearsph_runs(const std::vector<std::pair<std::string, json>>& jobs,
                                          const std::filesystem::path& out, int repeats) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  std::vector<ProcessRun> runs(jobs.size());
  std::vector<std::filesystem::path> dirs;
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    std::string stem = "plate_";
    stem += jobs[k].first;
    dirs.push_back(out / (stem + "_run"));
    const std::filesystem::path& dir = dirs.back();
    const std::filesystem::path file = out / (stem + "_job.json");
    std::ofstream(file) << jobs[k].second.dump(2) << "\n";
    std::string& command = runs[k].command;
    for (const std::string& part :
         {std::string("'"), self.string(), std::string("' run '"), file.string(),
          std::string("' --out '"), dir.string(), std::string("' --threads 1 --quiet")}) {
      command += part;
    }
  }
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t k = 0; k < jobs.size(); ++k) {
      ProcessRun& p = runs[k];
      if (!p.ok) continue;
      std::filesystem::remove_all(dirs[k], ec);
      const auto t0 = Clock::now();
      p.ok = std::system(p.command.c_str()) == 0;
      p.wall_s = std::min(p.wall_s, std::chrono::duration<double>(Clock::now() - t0).count());
    }
  }
  return runs;
}

// Ours on PySPH's plate, three ways: bare steps; a run in this process
// (stepping, history, analysis); and `gearsph run` as a user runs it, the
// whole process with the default output (start-up, set-up, 50 frames,
// history, summary).
struct OursOnPysphPlate {
  std::size_t particles = 0;
  std::int64_t planned_steps = 0;
  RunResult run;
  double run_rate = 0;  // particle-steps/s
  Timing bare;
  ProcessRun user;
  // The same process without frames and with 100 history rows: what the
  // default output adds is the difference (issue 30: at most 10 %).
  ProcessRun user_bare;
  double user_rate = 0;
  double output_share() const { return 1.0 - user_bare.wall_s / user.wall_s; }
};

OursOnPysphPlate time_ours(const json& job, const std::filesystem::path& out, int repeats) {
  OursOnPysphPlate o;
  {
    PreparedJob pj = prepare_job(job, 1);
    o.particles = pj.scene.sim.particles.n;
    o.planned_steps = pj.steps;
    o.run = run_job(pj);
  }
  o.run_rate = double(o.particles) * double(o.run.steps_done) / o.run.wall_s;
  for (int r = 0; r < repeats; ++r) {
    const Timing x = time_steps(job, 1, std::min<std::int64_t>(o.planned_steps, 4000));
    if (r == 0 || x.wall_s < o.bare.wall_s) o.bare = x;
  }
  // The user's run: the job file as written, every output at its default.
  json user_job = job;
  user_job.erase("output");
  json bare_job = job;
  bare_job["output"] = {{"frames", 0}, {"history_points", 100}};
  const std::vector<ProcessRun> runs =
      time_gearsph_runs({{"user", user_job}, {"bare", bare_job}}, out, std::max(repeats, 3));
  o.user = runs[0];
  o.user_bare = runs[1];
  o.user_rate = double(o.particles) * double(o.planned_steps) / o.user.wall_s;
  return o;
}

std::string percent_or_na(const json& v) {
  return v.is_number() ? fmt("%+.2f%%", 100.0 * v.get<double>()) : std::string("n/a");
}

json ours_row(const PysphSettings& s, const OursOnPysphPlate& o) {
  const json& a = o.run.summary.at("analysis");
  return {{"dt_s", s.dt},
          {"end_s", s.end_s},
          {"Vf", s.vf},
          {"kernel", "cubic_spline"},
          {"h_over_dx", 1.3},
          {"bare",
           {{"particles", o.bare.particles},
            {"steps", o.bare.steps},
            {"wall_s", o.bare.wall_s},
            {"particle_steps_per_s", o.bare.particle_steps_per_s()}}},
          {"ours",
           {{"particles", o.particles},
            {"steps", o.run.steps_done},
            {"wall_s", o.run.wall_s},
            {"particle_steps_per_s", o.run_rate},
            {"period_s", a.value("period_s", json())},
            {"period_error", a.value("period_error", json())}}},
          {"user_run",
           {{"command", o.user.command},
            {"ok", o.user.ok},
            {"particles", o.particles},
            {"steps", o.planned_steps},
            {"process_wall_s", o.user.wall_s},
            {"particle_steps_per_s", o.user_rate},
            {"bare_output_process_wall_s", o.user_bare.wall_s},
            {"output_share", o.user.ok && o.user_bare.ok ? json(o.output_share()) : json()}}}};
}

void print_ours(const PysphSettings& s, const OursOnPysphPlate& o) {
  std::printf(
      "2. Oscillating plate, ours against PySPH (dx 2 mm, cubic spline, h 1.3 dx, dt %.0e s, "
      "Vf %.2f, %g s, 1 thread)\n",
      s.dt, s.vf, s.end_s);
  std::printf("%-34s %9s %8s %9s %12s %12s\n", "code", "particles", "steps", "wall_s", "Mpart-st/s",
              "period_err");
  const Timing& bare = o.bare;
  std::printf("%-34s %9zu %8lld %9.3f %12.3f %12s\n", "gearsph, bare steps", bare.particles,
              static_cast<long long>(bare.steps), bare.wall_s, 1e-6 * bare.particle_steps_per_s(),
              "");
  const json& a = o.run.summary.at("analysis");
  std::printf("%-34s %9zu %8lld %9.3f %12.3f %12s\n", "gearsph, run in this process", o.particles,
              static_cast<long long>(o.run.steps_done), o.run.wall_s, 1e-6 * o.run_rate,
              percent_or_na(a.value("period_error", json())).c_str());
  std::printf("%-34s %9zu %8lld %9.3f %12.3f %12s\n",
              o.user.ok ? "gearsph run, default output" : "gearsph run (FAILED)", o.particles,
              static_cast<long long>(o.planned_steps), o.user.wall_s, 1e-6 * o.user_rate, "");
  const double bare_rate = double(o.particles) * double(o.planned_steps) / o.user_bare.wall_s;
  std::printf("%-34s %9zu %8lld %9.3f %12.3f %12s\n",
              o.user_bare.ok ? "gearsph run, no frames, 100 rows" : "gearsph run (FAILED)",
              o.particles, static_cast<long long>(o.planned_steps), o.user_bare.wall_s,
              1e-6 * bare_rate, "");
  if (o.user.ok && o.user_bare.ok) {
    std::printf("outputs: %.1f %% of the default run's wall time   (target <= 10 %%)\n",
                100.0 * o.output_share());
  }
}

// PySPH's time loop on the same plate (timed by its own "Run took", without
// start-up or compilation), printed and added to `row` with the ratios.
void compare_with_pysph(const BenchOptions& opt, const PysphSettings& s, const OursOnPysphPlate& o,
                        json& row) {
  const std::filesystem::path script = find_pysph_script(opt.pysph_script);
  if (opt.no_pysph) {
    row["pysph"] = {{"skipped", "--no-pysph"}};
    return;
  }
  if (script.empty()) {
    row["pysph"] = {{"skipped", "bench/pysph_plate.py not found (give --pysph-script)"}};
    std::printf("PySPH: bench/pysph_plate.py not found (give --pysph-script)\n");
    return;
  }
  const int every = opt.quick ? 1000000 : 100;  // tip samples for the period
  const PysphResult py =
      run_pysph(opt.python, script, std::filesystem::path(opt.out) / "pysph", s.vf, s.end_s, every);
  if (!py.ok) {
    row["pysph"] = {{"error", py.message}};
    std::printf("PySPH: %s\n", py.message.c_str());
    return;
  }
  const json& p = py.report;
  const double n = p.at("particles").get<double>(), steps = p.at("steps").get<double>();
  const double run_s = p.at("run_s").get<double>();
  const double rate = n * steps / run_s;
  const double bare_rate = o.bare.particle_steps_per_s();
  std::printf("%-34s %9.0f %8.0f %9.3f %12.3f %12s\n", "PySPH, its time loop", n, steps, run_s,
              1e-6 * rate, percent_or_na(p.value("period_error", json())).c_str());
  std::printf(
      "ratio to PySPH (particle-steps/s): bare %.1f, in this process %.1f, "
      "end to end %.1f   (target >= 30 end to end)\n",
      bare_rate / rate, o.run_rate / rate, o.user_rate / rate);
  row["pysph"] = p;
  row["pysph"]["particle_steps_per_s"] = rate;
  row["pysph"]["process_cpu_s"] = py.cpu_s;
  row["ratio"] = o.run_rate / rate;
  row["ratio_bare"] = bare_rate / rate;
  row["ratio_end_to_end"] = o.user.ok ? json(o.user_rate / rate) : json();
}

void bench_pysph_plate(const BenchOptions& opt, json& report) {
  const PysphSettings s = pysph_settings(opt.quick);
  const OursOnPysphPlate o =
      time_ours(pysph_plate_job(s, opt.quick), std::filesystem::path(opt.out), opt.repeats);
  json row = ours_row(s, o);
  print_ours(s, o);
  compare_with_pysph(opt, s, o, row);
  report["pysph_plate"] = row;
  std::printf("\n");
}

// ------------------------------------------ 3. cost and memory from 1e3 to 1e6 particles

json scaling_row(double target, const Timing& x) {
  std::printf("%9.0e %10zu %7lld %10.3f %13.1f %12.1f %12.0f %12.0f\n", target, x.particles,
              static_cast<long long>(x.steps), x.wall_s, x.ns_per_particle_step(),
              x.cpu_ns_per_particle_step(), x.rss_per_particle, x.peak_per_particle);
  return {{"target", target},
          {"particles", x.particles},
          {"pairs_per_step", x.pairs},
          {"steps", x.steps},
          {"wall_s", x.wall_s},
          {"cpu_s", x.cpu_s},
          {"ns_per_particle_step", x.ns_per_particle_step()},
          {"cpu_ns_per_particle_step", x.cpu_ns_per_particle_step()},
          {"rss_bytes_per_particle", x.rss_per_particle},
          {"peak_bytes_per_particle", x.peak_per_particle}};
}

// Per particle added between the two largest cases: what a particle costs
// without the fixed part (libraries, threads' stacks, the heap's first
// megabytes), which dominates the per-particle figure at 1e3-1e4.
void report_added_particle(const json& rows, json& report) {
  if (rows.size() < 2) return;
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

// The plate with the spacing for each count (N ~ 0.005 m^2 / dx^2), bare
// steps on 2 threads.
void bench_scaling(const BenchOptions& o, json& report) {
  std::printf("3. Scaling (plate, 2 threads, bare steps)\n");
  std::printf("%9s %10s %7s %10s %13s %12s %12s %12s\n", "target", "particles", "steps", "wall_s",
              "wall ns/p-st", "cpu ns/p-st", "rss B/part", "peak B/part");
  json rows = json::array();
  for (double target : {1e3, 1e4, 1e5, 1e6}) {
    if (target > o.max_particles) break;
    const double dx = std::sqrt(0.005 / target);
    // About 5e6 particle-steps each (--quick: 1e6), at least three steps.
    const std::int64_t steps =
        std::max<std::int64_t>(3, std::llround((o.quick ? 1e6 : 5e6) / target));
    rows.push_back(scaling_row(target, time_steps(plate_job(dx), 2, steps)));
  }
  report["scaling"] = rows;
  report_added_particle(rows, report);
  std::printf("\n");
}

// ------------------------------------------ 4. the seed paper's full case

// 1e6 steps of 4e-8 s, as `gearsph run` does it. --quick: the first 2 % of
// the steps, scaled. The scene is built for the full end time (it models
// the teeth that engage in it), so the step count is cut after preparing,
// not the end time. The paper's uniform lattice runs beside the default,
// alternated, the faster of two each (--quick), so that the default's cost
// per simulated millisecond is read as a ratio in one run.
struct FullCaseRun {
  std::size_t particles = 0;
  long long steps = 0;
  double wall_s = 0.0, cpu_s = 0.0, full_s = 0.0;
  std::string status;
};

FullCaseRun run_full_case(const json& job, double fraction) {
  PreparedJob pj = prepare_job(job, 2);
  pj.steps = std::llround(fraction * double(pj.steps));
  const double c0 = cpu_seconds();
  const RunResult r = run_job(pj);
  return {pj.scene.sim.particles.n,
          static_cast<long long>(r.steps_done),
          r.wall_s,
          cpu_seconds() - c0,
          r.wall_s / fraction,
          r.status};
}

void bench_full_case(const BenchOptions& o, json& report) {
  const double fraction = o.quick ? 0.02 : 1.0;
  json lattice_job = gear_job();
  lattice_job["discretization"] = {{"particles", "lattice"}};
  FullCaseRun graded, lattice;
  for (int r = 0; r < (o.quick ? 2 : 1); ++r) {
    const FullCaseRun g = run_full_case(gear_job(), fraction);
    const FullCaseRun l = run_full_case(lattice_job, fraction);
    if (r == 0 || g.wall_s < graded.wall_s) graded = g;
    if (r == 0 || l.wall_s < lattice.wall_s) lattice = l;
  }
  const double ratio = graded.full_s / lattice.full_s;
  std::printf(
      "4. Paper's gear case, 2 threads: the default, %zu particles, %lld steps, %.1f s wall, "
      "%.1f s CPU%s  (target < 60 s, stretch < 30 s)\n",
      graded.particles, graded.steps, graded.wall_s, graded.cpu_s,
      o.quick ? fmt(" -> full case %.0f s (scaled from 2 %%)", graded.full_s).c_str() : "");
  std::printf(
      "   the paper's lattice, %zu particles: %.1f s wall%s; the default costs %.2f times "
      "the lattice per simulated millisecond\n",
      lattice.particles, lattice.wall_s,
      o.quick ? fmt(" -> full case %.0f s", lattice.full_s).c_str() : "", ratio);
  report["full_case"] = {{"particles", graded.particles},
                         {"steps", graded.steps},
                         {"wall_s", graded.wall_s},
                         {"fraction_run", fraction},
                         {"full_case_wall_s", graded.full_s},
                         {"cpu_s", graded.cpu_s},
                         {"status", graded.status},
                         {"lattice",
                          {{"particles", lattice.particles},
                           {"steps", lattice.steps},
                           {"wall_s", lattice.wall_s},
                           {"full_case_wall_s", lattice.full_s},
                           {"status", lattice.status}}},
                         {"default_over_lattice", ratio}};
}

// ------------------------------------------ 5. a study through the service

#ifdef GEARSPH_WITH_SERVICE
// As design automation submits one: the seed paper's case N times (--quick: its
// first 2 ms), at the server's defaults.
void bench_study(const BenchOptions& o, json& report) {
  const double end_s = o.quick ? 0.002 : 0.04;
  try {
    const json st = study_throughput(std::filesystem::path(o.out) / "study", o.study_jobs, end_s);
    std::printf(
        "\n5. A study of %d paper's cases (%g s each) through gearsph serve on %d cores: "
        "%.1f s, %.2f job-times of %.1f s (ideal %.1f), %.0f jobs per hour (%d of %d "
        "jobs on one thread)\n",
        o.study_jobs, end_s, st.at("cores").get<int>(), st.at("study_wall_s").get<double>(),
        st.at("job_times").get<double>(), st.at("mean_job_time_s").get<double>(),
        st.at("ideal_job_times").get<double>(), st.at("jobs_per_hour").get<double>(),
        st.at("jobs_on_one_thread").get<int>(), o.study_jobs);
    report["study"] = st;
  } catch (const std::exception& e) {
    std::printf("\n5. The study through gearsph serve failed: %s\n", e.what());
    report["study"] = {{"error", e.what()}};
  }
}
#endif

int bench_main(Args& args) {
  const BenchOptions o = read_options(args);
  std::filesystem::create_directories(o.out);
  json report = start_report(o.quick);
  bench_throughput(o, report);
  bench_pysph_plate(o, report);
  bench_scaling(o, report);
  if (!o.skip_full) bench_full_case(o, report);
#ifdef GEARSPH_WITH_SERVICE
  if (!o.skip_study && o.study_jobs > 0) bench_study(o, report);
#endif
  write_file_atomic(std::filesystem::path(o.out) / "bench.json", report.dump(2) + "\n");
  std::printf("\nreport: %s/bench.json\n", o.out.c_str());
  return 0;
}

// ---------------------------------------------------------------- pareto

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
  pareto_sweeps(out, cases, quick, threads);
  return 0;
}

}  // namespace

// `gearsph bench [options]` or `gearsph bench pareto [options]`.
int cmd_bench(int argc, char** argv) {
  // The wait policy main() chose, or the caller's (docs/speed-accuracy-history.md).
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
