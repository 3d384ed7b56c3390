// Slurm as the engine that runs the jobs (`gearsph serve --dispatch slurm`):
// first the dispatcher's reading of Slurm's commands, against output the
// real commands printed (slurm-wlm 22.05, accounting off as in
// tests/scaleout/slurm.sh, and sacct's documented --parsable2 form); then a
// real single-node Slurm on loopback (tests/scaleout/slurm.sh) running jobs
// submitted through the API to completion, a cancellation, and the server
// killed and restarted while its Slurm job runs, and the FE stage of a
// Slurm job recorded as the server's own workers record it.
#include <cstdlib>
#include <fstream>

#include "server/slurm_dispatch.hpp"
#include "tests/scaleout/support.hpp"

namespace gearsph::server::testing {
namespace {

TEST(ScaleOutSlurmFormats, SbatchParsable) {
  EXPECT_EQ(parse_sbatch_parsable("1\n"), "1");
  EXPECT_EQ(parse_sbatch_parsable("4242;gearsph-test\n"), "4242");  // with a cluster name
  EXPECT_EQ(parse_sbatch_parsable("sbatch: warning: something\n17\n"), "17");
  EXPECT_FALSE(parse_sbatch_parsable("sbatch: error: Batch job submission failed\n"));
  EXPECT_FALSE(parse_sbatch_parsable(""));
}

TEST(ScaleOutSlurmFormats, SqueueLines) {
  // squeue --noheader --states=all --format=%i|%j|%T|%r, as printed by slurm-wlm 22.05.8.
  const std::string out =
      "3|gearsph-test1|CANCELLED|Priority\n"
      "1|gearsph-test1|RUNNING|None\n"
      "2|gearsph-test1|PENDING|Priority\n"
      "4|gearsph-0b5e8d3c-6c1f-4f57-9a3e-1f0c2a9d4e71|COMPLETED|None\n";
  const auto e = parse_squeue(out);
  ASSERT_EQ(e.size(), 4u);
  EXPECT_EQ(e[0].job_id, "3");
  EXPECT_EQ(e[0].state, "CANCELLED");
  EXPECT_EQ(e[2].reason, "Priority");
  EXPECT_EQ(e[3].name, "gearsph-0b5e8d3c-6c1f-4f57-9a3e-1f0c2a9d4e71");
  EXPECT_TRUE(parse_squeue("").empty());
  EXPECT_TRUE(parse_squeue("slurm_load_jobs error: Unable to contact slurm controller\n").empty());
}

TEST(ScaleOutSlurmFormats, SacctLines) {
  // sacct --noheader --parsable2 --allocations --format=JobID,State,ExitCode
  const auto rows = parse_sacct("12|COMPLETED|0:0\n13|CANCELLED by 0|0:15\n14|FAILED|3:0\n");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1].state, "CANCELLED");
  EXPECT_EQ(rows[2].exit_code, 3);
  // With accounting off sacct prints only this (and exits 1).
  EXPECT_TRUE(parse_sacct("Slurm accounting storage is disabled\n").empty());
}

TEST(ScaleOutSlurmFormats, StatesMapToOurs) {
  EXPECT_EQ(slurm_phase("PENDING"), SlurmPhase::queued);
  EXPECT_EQ(slurm_phase("REQUEUED"), SlurmPhase::queued);
  EXPECT_EQ(slurm_phase("RUNNING"), SlurmPhase::running);
  EXPECT_EQ(slurm_phase("COMPLETING"), SlurmPhase::running);
  EXPECT_EQ(slurm_phase("SUSPENDED"), SlurmPhase::running);
  for (const char* s : {"COMPLETED", "FAILED", "CANCELLED", "TIMEOUT", "NODE_FAIL", "PREEMPTED",
                        "OUT_OF_MEMORY", "BOOT_FAIL", "DEADLINE"}) {
    EXPECT_EQ(slurm_phase(s), SlurmPhase::ended) << s;
  }
  EXPECT_EQ(slurm_phase("SOMETHING_NEW"), SlurmPhase::unknown);
}

TEST(ScaleOutSlurmFormats, ProgressOfGearsphRun) {
  // What `gearsph run` prints on a non-terminal stderr.
  const auto p = parse_run_progress(
      "gearsph run: job: plate, 315 particles, 3973 steps of 1.26e-05 s (...), 1 threads\n"
      "[ 12.0%] step 477/3973  t = 0.006 s  wall 0.1 s  ETA 0.8 s\n"
      "[ 48.0%] step 1907/3973  t = 0.024 s  wall 0.5 s  ETA 0.5 s\n");
  ASSERT_TRUE(p);
  EXPECT_EQ(p->step, 1907);
  EXPECT_EQ(p->steps, 3973);
  EXPECT_DOUBLE_EQ(p->time_s, 0.024);
  EXPECT_FALSE(parse_run_progress("gearsph run: starting\n"));
}

TEST(ScaleOutSlurmFormats, BatchScriptRunsGearsphWithTheAllocatedCpus) {
  SlurmOptions o;
  o.gearsph = "/opt/gear sph/gearsph";
  o.cpus_per_job = 4;
  const std::string s = slurm_batch_script("abc", "/shared/jobs/abc", o);
  EXPECT_EQ(s.rfind("#!/bin/sh\n", 0), 0u);
  EXPECT_NE(s.find("#SBATCH --job-name=gearsph-abc\n"), std::string::npos);
  EXPECT_NE(s.find("#SBATCH --cpus-per-task=4\n"), std::string::npos);
  EXPECT_NE(s.find("#SBATCH --output=/shared/jobs/abc/.slurm/output.txt\n"), std::string::npos);
  EXPECT_NE(s.find("'/opt/gear sph/gearsph' run '/shared/jobs/abc/.slurm/job.json' --out "
                   "'/shared/jobs/abc' --threads \"$threads\""),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("threads=${SLURM_CPUS_PER_TASK:-"), std::string::npos);
  // The script itself is valid sh.
  TempDir dir;
  std::ofstream(dir.path() / "job.sh") << s;
  EXPECT_EQ(shell("sh -n " + (dir.path() / "job.sh").string()), 0);
}

// A single-node Slurm for each test, and the API with --dispatch slurm.
class ScaleOutSlurm : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* b : {"slurmctld", "slurmd", "munged", "sbatch", "squeue", "scancel"}) {
      if (shell(std::string("command -v ") + b) != 0) {
        GTEST_SKIP() << b << " is missing: apt-get install slurm-wlm munge";
      }
    }
    if (::geteuid() != 0) {
      GTEST_SKIP() << "a single-node Slurm needs root here (slurmd starts jobs as their owners, "
                      "munged runs as the munge user); run the tests as root";
    }
    slurm_ = std::make_unique<Engine>(script("slurm.sh"));
    ASSERT_TRUE(slurm_->started()) << slurm_->output();
    const std::string line = slurm_->last_line();
    ASSERT_EQ(line.rfind("SLURM_CONF=", 0), 0u) << slurm_->output();
    // The server and the Slurm commands find this cluster through SLURM_CONF.
    ::setenv("SLURM_CONF", line.substr(11).c_str(), 1);
  }
  void TearDown() override { ::unsetenv("SLURM_CONF"); }

  static std::vector<SlurmQueueEntry> queue() {
    const CommandResult r =
        run_command({"squeue", "--noheader", "--states=all", "--format=%i|%j|%T|%r"});
    return parse_squeue(r.out);
  }
  static std::optional<SlurmQueueEntry> slurm_job_of(const std::string& id) {
    for (const SlurmQueueEntry& e : queue()) {
      if (e.name == "gearsph-" + id) return e;
    }
    return std::nullopt;
  }
  static std::string state_of(const std::string& id) {
    const auto e = slurm_job_of(id);
    return e ? e->state : "(not in squeue)";
  }

  std::unique_ptr<Engine> slurm_;
};

TEST_F(ScaleOutSlurm, SubmittedJobsRunToCompletion) {
  ServerProcess api({"--dispatch", "slurm", "--threads-per-job", "1"});
  auto c = api.client();
  std::vector<std::string> ids;
  for (int i = 0; i < 3; ++i) ids.push_back(submit(c, tiny_job(0.01)));
  for (const std::string& id : ids) {
    const json s = wait_final(c, id);
    EXPECT_EQ(s.at("status"), "successful") << s.dump() << api.log();
    EXPECT_NE(s.at("message").get<std::string>().find("(Slurm job "), std::string::npos)
        << s.dump();
    EXPECT_EQ(s.at("attempts"), 1);
    const ClientResponse r = c.get("/jobs/" + id + "/results");
    EXPECT_EQ(r.status, 200u) << r.body;
    // One Slurm job per simulation, named after it, ended with status 0.
    const auto e = slurm_job_of(id);
    ASSERT_TRUE(e) << id;
    EXPECT_EQ(e->state, "COMPLETED");
    EXPECT_EQ(slurp(api.data() / "jobs" / id / ".slurm" / "exit"), "0\n");
    EXPECT_NE(slurp(api.data() / "jobs" / id / ".slurm" / "output.txt").find("gearsph run:"),
              std::string::npos);
  }
  expect_consistent_store(api.data());
}

// scontrol requeue: Slurm holds the job pending again, and so does the job
// store (accepted, not "running 30 %" for minutes); dismissing it then
// cancels the pending Slurm job.
TEST_F(ScaleOutSlurm, ARequeuedJobShowsQueued) {
  ServerProcess api({"--dispatch", "slurm", "--threads-per-job", "1"});
  auto c = api.client();
  const std::string id = submit(c, tiny_job(20.0));
  const json running = wait_for(c, id, [](const json& s) { return s.at("status") == "running"; });
  ASSERT_EQ(running.at("status"), "running") << running.dump() << api.log();
  const auto slurm = slurm_job_of(id);
  ASSERT_TRUE(slurm);
  std::string out;
  ASSERT_EQ(shell("scontrol requeue " + slurm->job_id, &out), 0) << out;
  const json queued = wait_for(
      c, id, [](const json& s) { return s.at("status") == "accepted"; }, std::chrono::seconds(30));
  EXPECT_EQ(queued.at("status"), "accepted") << queued.dump();
  EXPECT_NE(
      queued.at("message").get<std::string>().find("queued again in Slurm as job " + slurm->job_id),
      std::string::npos)
      << queued.dump();
  EXPECT_EQ(queued.at("progress"), 0);
  const std::string state = state_of(id);
  EXPECT_TRUE(slurm_phase(state) == SlurmPhase::queued) << state;
  ASSERT_EQ(c.request("DELETE", "/jobs/" + id).status, 200u);
  const json s = wait_for(c, id, [](const json& d) {
    return d.at("message").get<std::string>().find("was cancelled") != std::string::npos;
  });
  EXPECT_EQ(s.at("status"), "dismissed") << s.dump();
}

// Two API nodes dispatching to Slurm from one PostgreSQL store, with an
// sbatch that takes 1.5 s to answer (a busy controller): each job is
// submitted to Slurm once, and each outcome is its own run's.
TEST_F(ScaleOutSlurm, TwoApiNodesSubmitEachJobOnce) {
  std::string out;
  if (shell("ls /usr/lib/postgresql/*/bin/initdb", &out) != 0) {
    GTEST_SKIP() << "PostgreSQL server binaries are missing; apt-get install postgresql";
  }
  Engine pg(script("postgres.sh"));
  ASSERT_TRUE(pg.started()) << pg.output();
  TempDir wrappers, results;
  const std::string real_sbatch = [] {
    std::string path;
    shell("command -v sbatch", &path);
    while (!path.empty() && path.back() == '\n') path.pop_back();
    return path;
  }();
  std::ofstream(wrappers.path() / "sbatch")
      << "#!/bin/sh\nsleep 1.5\nexec " << real_sbatch << " \"$@\"\n";
  fs::permissions(wrappers.path() / "sbatch", fs::perms::owner_all);
  const std::string path = std::getenv("PATH");
  ::setenv("PATH", (wrappers.path().string() + ":" + path).c_str(), 1);
  struct RestorePath {
    std::string path;
    ~RestorePath() { ::setenv("PATH", path.c_str(), 1); }
  } restore{path};
  const std::vector<std::string> args = {
      "--dispatch", "slurm",        "--threads-per-job", "1",
      "--store",    pg.last_line(), "--results",         results.path().string()};
  ServerProcess a(args), b(args);
  auto ca = a.client();
  auto cb = b.client();
  std::vector<std::string> ids;
  for (int i = 0; i < 6; ++i) ids.push_back(submit(i % 2 ? cb : ca, tiny_job(0.02)));
  for (const std::string& id : ids) {
    const json s = wait_final(ca, id, std::chrono::seconds(180));
    EXPECT_EQ(s.at("status"), "successful") << s.dump() << a.log() << b.log();
    EXPECT_EQ(s.at("attempts"), 1) << s.dump();
    const json summary = json::parse(ca.get("/jobs/" + id + "/files/summary.json").body);
    EXPECT_EQ(summary.at("status"), "completed");
    EXPECT_EQ(summary.at("steps"), s.at("steps")) << summary.dump().substr(0, 300);
  }
  std::map<std::string, int> submissions;
  for (const SlurmQueueEntry& e : queue()) ++submissions[e.name];
  for (const std::string& id : ids) {
    EXPECT_EQ(submissions["gearsph-" + id], 1) << id << "\n" << a.log() << b.log();
  }
}

TEST_F(ScaleOutSlurm, DismissCancelsTheSlurmJob) {
  ServerProcess api({"--dispatch", "slurm", "--threads-per-job", "1"});
  auto c = api.client();
  const std::string id = submit(c, tiny_job(20.0));
  const json running = wait_for(c, id, [](const json& s) { return s.at("status") == "running"; });
  ASSERT_EQ(running.at("status"), "running") << running.dump() << api.log();
  ASSERT_EQ(state_of(id), "RUNNING");
  ASSERT_EQ(c.request("DELETE", "/jobs/" + id).status, 200u);
  const json s = wait_for(c, id, [](const json& d) {
    return d.at("message").get<std::string>().find("was cancelled") != std::string::npos;
  });
  EXPECT_EQ(s.at("status"), "dismissed") << s.dump();
  const auto deadline = Clock::now() + std::chrono::seconds(30);
  std::string state;
  while (Clock::now() < deadline) {
    state = state_of(id);
    if (state == "CANCELLED") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_EQ(state, "CANCELLED");
  EXPECT_FALSE(fs::exists(api.data() / "jobs" / id / "summary.json"));
}

TEST_F(ScaleOutSlurm, ServerRestartKeepsTrackOfSubmittedJobs) {
  ServerProcess api({"--dispatch", "slurm", "--threads-per-job", "1"});
  auto c = api.client();
  // About 4 s of one core: the server sees it running before it ends.
  const std::string id = submit(c, tiny_job(1.0));
  const json running = wait_for(c, id, [](const json& s) { return s.at("status") != "accepted"; });
  ASSERT_EQ(running.at("status"), "running") << running.dump() << api.log();
  EXPECT_EQ(api.stop(SIGKILL), 128 + SIGKILL);
  // The Slurm job runs on without the server and ends.
  const auto deadline = Clock::now() + std::chrono::seconds(120);
  while (Clock::now() < deadline && state_of(id) != "COMPLETED") {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_EQ(state_of(id), "COMPLETED");
  api.start();
  auto c2 = api.client();
  const json s = wait_final(c2, id);
  EXPECT_EQ(s.at("status"), "successful") << s.dump() << api.log();
  EXPECT_EQ(s.at("attempts"), 1);  // tracked, not run again
  EXPECT_EQ(c2.get("/jobs/" + id + "/results").status, 200u);
}

// Issue 49: a Slurm job's FE stage is counted and its failure recorded as
// for the server's own workers (tests/test_fe_server.cpp,
// TheFeStageIsCountedAndItsFailureShown). The stand-in gmsh waits for the
// test's word, then fails; the Slurm job inherits the server's environment
// (sbatch --export=ALL, the default).
TEST_F(ScaleOutSlurm, TheFeStageOfASlurmJobIsRecorded) {
  TempDir dir;
  const fs::path go = dir.path() / "gmsh.go";
  const fs::path gmsh = dir.path() / "gmsh";
  std::ofstream(gmsh) << "#!/bin/sh\nwhile [ ! -f " << go.string()
                      << " ]; do sleep 0.05; done\necho 'meshing failed' >&2\nexit 1\n";
  fs::permissions(gmsh, fs::perms::owner_all);
  ::setenv("GEARSPH_GMSH", gmsh.c_str(), 1);
  ::setenv("GEARSPH_CCX", "/bin/true", 1);
  ServerProcess api({"--dispatch", "slurm", "--threads-per-job", "1"});
  ::unsetenv("GEARSPH_GMSH");
  ::unsetenv("GEARSPH_CCX");
  auto c = api.client();
  const json job = {{"name", "fe-check-slurm"},
                    {"scene",
                     {{"type", "rack_pinion"},
                      {"quasi_static", true},
                      {"fe_check", true},
                      {"pinion", {{"omega_rad_s", 0}}},
                      {"rack", {{"velocity_m_s", 0}, {"load_N", 1000}}}}},
                    {"time", {{"end_s", 2e-4}}}};
  const std::string id = submit(c, job);
  ASSERT_FALSE(id.empty());

  // In the FE stage: not 100 %, time left, the stage's clock running.
  const json fe = wait_for(
      c, id,
      [](const json& s) {
        return is_final(s.at("status")) ||
               (s.at("stage") == "fe_check" && s.at("fe_check").value("wall_s", 0.0) >= 1.0);
      },
      std::chrono::seconds(300));
  ASSERT_EQ(fe.at("stage"), "fe_check") << fe.dump() << api.log();
  EXPECT_EQ(fe.at("status"), "running");
  EXPECT_EQ(fe.at("fe_check").at("status"), "running") << fe.dump();
  EXPECT_LT(fe.at("progress").get<int>(), 100);
  EXPECT_GT(fe.at("eta_s").get<double>(), 0.0) << fe.dump();
  EXPECT_GE(fe.at("stage_wall_s").at("fe_check").get<double>(), 1.0) << fe.dump();
  std::ofstream(go) << "go\n";

  // The SPH result stands; the failed check is in the status and the message.
  const json final = wait_final(c, id, std::chrono::seconds(120));
  ASSERT_EQ(final.at("status"), "successful") << final.dump() << api.log();
  EXPECT_EQ(final.at("progress"), 100);
  const json& check = final.at("fe_check");
  ASSERT_TRUE(check.is_object()) << final.dump();
  EXPECT_EQ(check.at("status"), "failed") << final.dump();
  EXPECT_NE(check.at("message").get<std::string>().find("gmsh"), std::string::npos) << check.dump();
  EXPECT_GT(check.at("estimate_s").get<double>(), 0.0);
  EXPECT_EQ(check.at("basis"), "fallback");
  const std::string message = final.at("message").get<std::string>();
  EXPECT_NE(message.find("the FE check failed"), std::string::npos) << message;
  EXPECT_NE(message.find("(Slurm job "), std::string::npos) << message;
  // At least what the running job showed (the time since the output's last
  // line, on the same clock), less the output's write.
  const double fe_wall = final.at("stage_wall_s").at("fe_check").get<double>();
  EXPECT_GE(fe_wall, fe.at("stage_wall_s").at("fe_check").get<double>() - 0.05) << final.dump();
  EXPECT_NEAR(final.at("wall_s").get<double>(),
              final.at("stage_wall_s").at("sph").get<double>() + fe_wall, 1e-6);
}

}  // namespace
}  // namespace gearsph::server::testing
