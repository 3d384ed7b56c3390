// The divergence guard (validation.md section 9) and the CLI contract:
// gearsph run writes summary.json and history.csv with stable keys.
#include <gtest/gtest.h>

#include <algorithm>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

#include "solver/job/job.hpp"
#include "solver/run/runner.hpp"

namespace gearsph {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

json unstable_plate() {
  // Three times the stable Courant number, deliberately (allow_unstable).
  return {{"scene", {{"type", "plate"}, {"length_m", 0.1}, {"thickness_m", 0.01}}},
          {"discretization", {{"spacing_m", 0.002}}},
          {"time", {{"end_s", 0.01}, {"cfl", 1.6}, {"allow_unstable", true}}}};
}

TEST(Guard, UnstableRunStopsNamingStepParticleAndQuantity) {
  PreparedJob job = prepare_job(unstable_plate(), 1);
  ASSERT_GT(job.time_step.dt, 2.5 * job.time_step.dt_limit);
  const RunResult r = run_job(job);
  EXPECT_EQ(r.status, "diverged");
  EXPECT_LT(r.steps_done, job.steps);
  EXPECT_NE(r.message.find("diverged at step"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("particle"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find(" = "), std::string::npos) << r.message;  // quantity = value
  // What was recorded before the blow-up is kept, and says so.
  EXPECT_GE(r.history.rows(), 1u);
  EXPECT_EQ(r.summary.at("status"), "diverged");
  EXPECT_EQ(r.summary.at("message"), r.message);
}

TEST(Guard, StableRunCompletes) {
  json job_json = unstable_plate();
  job_json["time"] = {{"end_s", 0.01}};
  PreparedJob job = prepare_job(job_json, 1);
  const RunResult r = run_job(job);
  EXPECT_EQ(r.status, "completed") << r.message;
  EXPECT_EQ(r.steps_done, job.steps);
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int run_cli(const std::string& args) {
  const std::string cmd = std::string(GEARSPH_BINARY) + " " + args + " 2>/dev/null";
  const int status = std::system(cmd.c_str());
  return WEXITSTATUS(status);
}

// Output of `gearsph ARGS` (stdout) and its exit status.
std::pair<std::string, int> cli_output(const std::string& args) {
  const std::string cmd = std::string(GEARSPH_BINARY) + " " + args + " 2>/dev/null";
  std::string out;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return {"", -1};
  char buf[4096];
  for (std::size_t got; (got = std::fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, got);
  const int status = pclose(pipe);
  return {out, WEXITSTATUS(status)};
}

// What `gearsph ARGS` writes to stderr, and its exit status.
std::pair<std::string, int> cli_errors(const std::string& args) {
  const std::string cmd = std::string(GEARSPH_BINARY) + " " + args + " 2>&1 >/dev/null";
  std::string out;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return {"", -1};
  char buf[4096];
  for (std::size_t got; (got = std::fread(buf, 1, sizeof buf, pipe)) > 0;) out.append(buf, got);
  const int status = pclose(pipe);
  return {out, WEXITSTATUS(status)};
}

// Every command's seconds options are read by one parser; each keeps its
// own range and says it, before anything starts.
TEST(Cli, SecondsOptionsRefuseValuesOutsideTheirRange) {
  // worker, serve and submit are the service's commands: a build without the
  // service (the sanitizer build, GEARSPH_SERVICE=OFF) has none of them.
  if (cli_errors("worker").first.find("unknown command") != std::string::npos) {
    GTEST_SKIP() << "this build has no service commands";
  }
  const fs::path dir = fs::temp_directory_path() / "gearsph_cli_seconds";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string worker = "worker --store sqlite:" + (dir / "jobs.db").string() + " --results " +
                             (dir / "jobs").string();
  const std::pair<std::string, std::string> cases[] = {
      {worker + " --lease 0", "--lease takes seconds (> 0), not '0'"},
      {worker + " --poll x", "--poll takes seconds (> 0), not 'x'"},
      {worker + " --job-grace 90000", "--job-grace takes seconds (0 to 86400), not '90000'"},
      {"serve --data " + (dir / "data").string() + " --idle-timeout 0",
       "--idle-timeout takes seconds (> 0), not '0'"},
      {"submit --server http://127.0.0.1:9 --retry-for x " + (dir / "job.json").string(),
       "--retry-for takes seconds (0 or more), not 'x'"},
  };
  for (const auto& [args, message] : cases) {
    const auto [err, status] = cli_errors(args);
    EXPECT_EQ(status, 2) << args << "\n" << err;
    EXPECT_NE(err.find(message), std::string::npos) << args << "\n" << err;
  }
  fs::remove_all(dir);
}

TEST(Cli, HelpAfterACommandPrintsThatCommandsUsage) {
  const auto [run, run_status] = cli_output("run --help");
  EXPECT_EQ(run_status, 0);
  EXPECT_NE(run.find("gearsph run JOB.json --out DIR"), std::string::npos) << run;
  EXPECT_EQ(run.find("gearsph serve"), std::string::npos) << "only the command's own lines";
  const auto [bench, bench_status] = cli_output("bench pareto -h");
  EXPECT_EQ(bench_status, 0);
  // Both bench lines: `gearsph bench` and `gearsph bench pareto`.
  EXPECT_NE(bench.find("gearsph bench [--quick]"), std::string::npos) << bench;
  EXPECT_NE(bench.find("gearsph bench pareto --out DIR"), std::string::npos) << bench;
  const auto [unknown, unknown_status] = cli_output("frobnicate --help");
  EXPECT_EQ(unknown_status, 0);
  EXPECT_NE(unknown.find("usage:"), std::string::npos) << "the whole usage for an unknown command";
}

TEST(Cli, RunWritesSummaryAndHistory) {
  const fs::path dir = fs::temp_directory_path() / "gearsph_cli_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const json job = {{"name", "cli-plate"},
                    {"scene", {{"type", "plate"}, {"length_m", 0.1}, {"thickness_m", 0.01}}},
                    {"discretization", {{"spacing_m", 0.002}}},
                    {"time", {{"end_s", 0.02}}}};
  std::ofstream(dir / "job.json") << job.dump();
  ASSERT_EQ(run_cli("run " + (dir / "job.json").string() + " --out " + (dir / "out").string() +
                    " --threads 1"),
            0);
  const json summary = json::parse(slurp(dir / "out/summary.json"));
  for (const char* key : {"particles", "steps", "dt_s", "wall_s", "max_von_mises_Pa", "analysis",
                          "particles_by_body", "status"}) {
    EXPECT_TRUE(summary.contains(key)) << key;
  }
  EXPECT_EQ(summary.at("name"), "cli-plate");
  EXPECT_TRUE(summary.at("analysis").contains("reference_period_s"));
  EXPECT_TRUE(summary.at("analysis").contains("period_s"));
  const std::string csv = slurp(dir / "out/history.csv");
  const std::string header = csv.substr(0, csv.find('\n'));
  EXPECT_EQ(header.rfind("time_s,", 0), 0u) << header;
  EXPECT_NE(header.find("tip_y_m"), std::string::npos) << header;
  EXPECT_NE(header.find("tip_vy_m_s"), std::string::npos) << header;
  fs::remove_all(dir);
}

// `gearsph geometry` draws graded particles as they are: the title gives
// the range of spacings, and each dot is sized by its own particle's
// spacing (the fillets' dots smaller than the rack's back).
TEST(Cli, GeometryDrawsGradedParticlesAtTheirOwnSpacing) {
  const fs::path dir = fs::temp_directory_path() / "gearsph_cli_geometry";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "job.json") << json{{"scene", {{"type", "rack_pinion"}}}}.dump();
  ASSERT_EQ(run_cli("geometry " + (dir / "job.json").string() + " --out " + (dir / "g").string()),
            0);
  const std::string svg = slurp(dir / "g/geometry.svg");
  EXPECT_NE(svg.find("particles, spacing 0.477 to 1.000 mm"), std::string::npos)
      << svg.substr(0, 400);
  // Dot radii in px: the largest over the smallest is about the spacings'
  // ratio, 1.000 / 0.477.
  double smallest = 1e300, largest = 0.0;
  for (std::size_t at = svg.find(" r=\""); at != std::string::npos;
       at = svg.find(" r=\"", at + 1)) {
    const double r = std::stod(svg.substr(at + 4));
    smallest = std::min(smallest, r);
    largest = std::max(largest, r);
  }
  ASSERT_GT(smallest, 0.0);
  EXPECT_NEAR(largest / smallest, 1.0 / 0.477, 0.1);
  const std::string csv = slurp(dir / "g/particles.csv");
  // A header, then as many particles as the title counts.
  const std::size_t title = svg.find("(rack_pinion): ");
  ASSERT_NE(title, std::string::npos);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + std::stol(svg.substr(title + 15)));
  fs::remove_all(dir);
}

TEST(Cli, InvalidJobExitsWithTwoAndWritesNothing) {
  const fs::path dir = fs::temp_directory_path() / "gearsph_cli_bad";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "job.json") << R"({"scene": {"type": "plate", "Vf": -1}})";
  EXPECT_EQ(run_cli("run " + (dir / "job.json").string() + " --out " + (dir / "out").string()), 2);
  EXPECT_FALSE(fs::exists(dir / "out/summary.json"));
  EXPECT_EQ(run_cli("run"), 2);
  EXPECT_EQ(run_cli("frobnicate"), 2);
  fs::remove_all(dir);
}

TEST(Cli, DivergedRunExitsWithThreeAndKeepsItsRecord) {
  const fs::path dir = fs::temp_directory_path() / "gearsph_cli_diverged";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "job.json") << unstable_plate().dump();
  EXPECT_EQ(run_cli("run " + (dir / "job.json").string() + " --out " + (dir / "out").string()), 3);
  const json summary = json::parse(slurp(dir / "out/summary.json"));
  EXPECT_EQ(summary.at("status"), "diverged");
  EXPECT_TRUE(fs::exists(dir / "out/history.csv"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gearsph
