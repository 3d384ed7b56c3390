// What an operator uses on a single server: /metrics in the Prometheus text
// format, the retention setting, and a warm shutdown (--job-grace) that lets
// a running job finish. (The same on many machines: test_scaleout_*.cpp.)
#include <regex>

#include "tests/test_server_support.hpp"

namespace gearsph::server::testing {
namespace {

// The value of one sample line ("name{labels} value"), or -1 if absent.
double sample(const std::string& text, const std::string& series) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(series + " ", 0) == 0) return std::stod(line.substr(series.size() + 1));
  }
  return -1;
}

TEST(ServerOperations, MetricsInThePrometheusTextFormat) {
  ServerProcess server({"--workers", "1", "--threads-per-job", "1"});
  auto c = server.client();
  const std::string id = submit(c, tiny_job());
  EXPECT_EQ(wait_final(c, id).at("status"), "successful");
  // The queue counts are refreshed every second.
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  const ClientResponse r = c.get("/metrics");
  ASSERT_EQ(r.status, 200u);
  EXPECT_EQ(r.header("content-type"), "text/plain; version=0.0.4");
  const std::string& m = r.body;
  EXPECT_EQ(sample(m, "gearsph_jobs{status=\"successful\"}"), 1) << m;
  EXPECT_EQ(sample(m, "gearsph_jobs{status=\"accepted\"}"), 0) << m;
  EXPECT_EQ(sample(m, "gearsph_store_up"), 1) << m;
  EXPECT_EQ(sample(m, "gearsph_job_wall_seconds_count"), 1) << m;
  EXPECT_EQ(sample(m, "gearsph_job_wall_seconds_bucket{le=\"+Inf\"}"), 1) << m;
  EXPECT_GT(sample(m, "gearsph_job_wall_seconds_sum"), 0) << m;
  EXPECT_GE(sample(m, "gearsph_http_requests_total"), 2) << m;
  EXPECT_EQ(sample(m, "gearsph_requeues_total"), 0) << m;
  // Every family is announced with HELP and TYPE; every sample line is
  // "name[{labels}] number".
  const std::regex sample_line(R"(^[a-z_]+(\{[a-z_]+="[^"]*"\})? [-+0-9.eE]+$)");
  std::istringstream in(m);
  std::string line;
  int samples = 0;
  while (std::getline(in, line)) {
    if (line.rfind("# HELP ", 0) == 0 || line.rfind("# TYPE ", 0) == 0) continue;
    EXPECT_TRUE(std::regex_match(line, sample_line)) << line;
    ++samples;
  }
  EXPECT_GT(samples, 15);
  // The log: a UTC time and a level on every line the service writes.
  const std::regex log_line(
      R"(^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z (INFO |WARN |ERROR) gearsph serve: .+$)");
  std::istringstream log(server.log());
  int lines = 0;
  while (std::getline(log, line)) {
    if (line.find(": job ") == std::string::npos) continue;  // the jobs' lines
    EXPECT_TRUE(std::regex_match(line, log_line)) << line;
    ++lines;
  }
  EXPECT_GE(lines, 2) << server.log();  // running, successful
}

// Jobs that ended longer ago than the retention go with their files.
TEST(ServerOperations, RetentionDeletesEndedJobsAndTheirFiles) {
  // 0.00002 days: 1.7 s. The first pruning runs 5 s after the start.
  ServerProcess server({"--workers", "1", "--threads-per-job", "1", "--retention-days", "0.00002"});
  auto c = server.client();
  const std::string id = submit(c, tiny_job());
  EXPECT_EQ(wait_final(c, id).at("status"), "successful");
  // Asked through the API first: it publishes a recorded attempt whose
  // worker has not yet renamed its directory (attempt_dirs.cpp).
  ASSERT_EQ(c.get("/jobs/" + id + "/files/summary.json").status, 200u);
  ASSERT_TRUE(fs::exists(server.data() / "jobs" / id / "summary.json"));
  const auto deadline = Clock::now() + std::chrono::seconds(30);
  while (c.get("/jobs/" + id).status != 404 && Clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  EXPECT_EQ(c.get("/jobs/" + id).status, 404u);
  EXPECT_FALSE(fs::exists(server.data() / "jobs" / id));
  EXPECT_NE(server.log().find("deleted 1 job(s) that ended over"), std::string::npos)
      << server.log();
  EXPECT_EQ(sample(c.get("/metrics").body, "gearsph_jobs_pruned_total"), 1);
}

// SIGTERM with --job-grace: the running job finishes and is recorded, the
// server then exits; started again, it shows the job successful at its
// first attempt.
TEST(ServerOperations, AWarmShutdownLetsTheRunningJobFinish) {
  ServerProcess server({"--workers", "1", "--threads-per-job", "1", "--job-grace", "60"});
  auto c = server.client();
  const std::string id = submit(c, tiny_job(1.0));  // 2-5 s of one core
  wait_for(c, id, [](const json& s) { return s.value("progress", 0) >= 5; });
  EXPECT_EQ(server.stop(SIGTERM, std::chrono::seconds(60)), 0) << server.log();
  EXPECT_NE(server.log().find("letting 1 running job(s) finish"), std::string::npos)
      << server.log();
  server.start();
  auto c2 = server.client();
  const json s = c2.get("/jobs/" + id).json();
  EXPECT_EQ(s.at("status"), "successful") << s.dump();
  EXPECT_EQ(s.at("attempts"), 1);
}

}  // namespace
}  // namespace gearsph::server::testing
