// The FE check in the job service: a job that asks for it is refused with
// 501 where gmsh or CalculiX is missing, with 400 where it does not apply,
// and run (its fe_comparison in the summary, its files beside the run's)
// where the tools are.
#include <signal.h>

#include <cstdlib>
#include <fstream>
#include <memory>
#include <thread>

#include "fe/external_program.hpp"
#include "tests/test_server_support.hpp"

namespace gearsph::server::testing {
namespace {

json static_gear_job(double end_s) {
  return {{"name", "fe-check-service"},
          {"scene",
           {{"type", "rack_pinion"},
            {"quasi_static", true},
            {"fe_check", true},
            {"pinion", {{"omega_rad_s", 0}}},
            {"rack", {{"velocity_m_s", 0}, {"load_N", 1000}}}}},
          {"time", {{"end_s", end_s}}}};
}

// A server whose gmsh is the stand-in shell script `body` (ccx: /bin/true),
// the environment put back once the server runs.
std::unique_ptr<ServerProcess> server_with_stand_in_gmsh(const fs::path& script,
                                                         const std::string& body) {
  std::ofstream(script) << "#!/bin/sh\n" << body;
  fs::permissions(script, fs::perms::owner_all);
  ::setenv("GEARSPH_GMSH", script.c_str(), 1);
  ::setenv("GEARSPH_CCX", "/bin/true", 1);
  auto server = std::make_unique<ServerProcess>(std::vector<std::string>{"--threads-per-job", "1"});
  ::unsetenv("GEARSPH_GMSH");
  ::unsetenv("GEARSPH_CCX");
  return server;
}

TEST(ServerFe, JobsAskingForTheCheckWithoutTheToolsAnswer501) {
  // The server inherits this environment: ccx is "missing" for it.
  ::setenv("GEARSPH_CCX", "/nonexistent/ccx", 1);
  ServerProcess server({"--threads-per-job", "1"});
  ::unsetenv("GEARSPH_CCX");
  auto c = server.client();
  const ClientResponse r = c.post_json("/jobs", static_gear_job(1e-4).dump());
  ASSERT_EQ(r.status, 501u) << r.body;
  EXPECT_EQ(r.header("Content-Type"), "application/problem+json");
  const json p = r.json();
  EXPECT_EQ(p.at("type"), "urn:gearsph:problem:fe-unavailable");
  EXPECT_EQ(p.at("errors").at(0).at("pointer"), "/scene/fe_check");
  EXPECT_NE(p.at("detail").get<std::string>().find("FE unavailable"), std::string::npos);
  EXPECT_NE(p.at("detail").get<std::string>().find("ccx"), std::string::npos);
  // Not applicable (a dynamic run) is the job's fault: 400 naming the field.
  json dynamic = static_gear_job(1e-4);
  dynamic["scene"]["quasi_static"] = false;
  const ClientResponse d = c.post_json("/jobs", dynamic.dump());
  ASSERT_EQ(d.status, 400u) << d.body;
  EXPECT_EQ(d.json().at("errors").at(0).at("pointer"), "/scene/fe_check");
  // Jobs without the check are taken as before.
  EXPECT_EQ(c.post_json("/jobs", tiny_job().dump()).status, 201u);
  // N7: the preview says the same, rather than previewing a job POST /jobs refuses.
  const json preview = c.post_json("/preview", static_gear_job(1e-4).dump()).json();
  EXPECT_FALSE(preview.at("accepted").get<bool>()) << preview.dump();
  EXPECT_EQ(preview.at("errors").at(0).at("pointer"), "/scene/fe_check");
}

// N2: a hung gmsh (a stand-in script that never ends) is stopped when its
// job is dismissed, not after the tool's 300 s timeout.
TEST(ServerFe, DismissingAJobStopsAHungTool) {
  TempDir dir;
  const fs::path pid_file = dir.path() / "gmsh.pid";
  const fs::path script = dir.path() / "gmsh";
  const auto server = server_with_stand_in_gmsh(
      script, "echo $$ > " + pid_file.string() + ".tmp\nmv " + pid_file.string() + ".tmp " +
                  pid_file.string() + "\nexec sleep 300\n");
  auto c = server->client();
  const std::string id = submit(c, static_gear_job(2e-4));
  ASSERT_FALSE(id.empty());
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(300);
  while (!fs::exists(pid_file) && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_TRUE(fs::exists(pid_file)) << server->log();
  const pid_t tool = std::stoi(slurp(pid_file));
  ASSERT_EQ(::kill(tool, 0), 0);
  EXPECT_EQ(c.request("DELETE", "/jobs/" + id).status, 200u);
  // Gone well before the tool's timeout; a zombie (its parent, the server,
  // reaps it) counts as gone.
  bool gone = false;
  for (int i = 0; i < 200 && !gone; ++i) {
    const std::string stat = slurp("/proc/" + std::to_string(tool) + "/stat");
    gone = stat.empty() || stat.find(") Z") != std::string::npos;
    if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_TRUE(gone) << "the stand-in gmsh still runs 20 s after the DELETE";
  const json final = wait_final(c, id, std::chrono::seconds(60));
  EXPECT_EQ(final.at("status"), "dismissed") << final.dump();
}

// Item 4 of the second review: the FE stage counts in the job's progress,
// ETA and wall time, and a failed check shows in the job's status, its
// events and its message (docs/api.md, The FE stage). The stand-in gmsh
// waits for the test's word, then fails.
TEST(ServerFe, TheFeStageIsCountedAndItsFailureShown) {
  TempDir dir;
  const fs::path started = dir.path() / "gmsh.started";
  const fs::path go = dir.path() / "gmsh.go";
  const fs::path script = dir.path() / "gmsh";
  const auto server = server_with_stand_in_gmsh(
      script, "touch " + started.string() + "\nwhile [ ! -f " + go.string() +
                  " ]; do sleep 0.05; done\necho 'meshing failed' >&2\nexit 1\n");
  auto c = server->client();

  // The preview's estimate counts the stage.
  const json preview = c.post_json("/preview", static_gear_job(2e-4).dump()).json();
  ASSERT_TRUE(preview.at("accepted").get<bool>()) << preview.dump();
  const json& estimate = preview.at("run_time");
  const double fe_estimate = estimate.at("fe_check_s").get<double>();
  EXPECT_GT(fe_estimate, 0.0);
  EXPECT_DOUBLE_EQ(estimate.at("wall_s").get<double>(),
                   estimate.at("sph_s").get<double>() + fe_estimate);

  const std::string id = submit(c, static_gear_job(2e-4));
  ASSERT_FALSE(id.empty());
  const json queued = c.get("/jobs/" + id).json();
  EXPECT_EQ(queued.at("fe_check").at("status"), "pending") << queued.dump();

  // In the SPH stage (if the poll sees it): the FE stage still to come is in the ETA.
  const json sph = wait_for(
      c, id, [](const json& s) { return !s.at("stage").is_null() || is_final(s.at("status")); },
      std::chrono::seconds(300));
  if (sph.at("stage") == "sph") {
    EXPECT_EQ(sph.at("fe_check").at("status"), "pending") << sph.dump();
    EXPECT_GT(sph.at("fe_check").at("eta_s").get<double>(), 0.0) << sph.dump();
    EXPECT_GE(sph.at("eta_s").get<double>(), sph.at("fe_check").at("eta_s").get<double>());
  }

  // In the FE stage: not 100 %, time left, the wall time growing past the SPH run's.
  const json fe = wait_for(
      c, id, [](const json& s) { return s.at("stage") == "fe_check" || is_final(s.at("status")); },
      std::chrono::seconds(300));
  ASSERT_EQ(fe.at("stage"), "fe_check") << fe.dump();
  EXPECT_EQ(fe.at("status"), "running");
  EXPECT_LT(fe.at("progress").get<int>(), 100);
  EXPECT_GT(fe.at("eta_s").get<double>(), 0.0) << fe.dump();
  EXPECT_EQ(fe.at("fe_check").at("status"), "running");
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(started) && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(fs::exists(started)) << server->log();
  const double sph_wall = fe.at("stage_wall_s").at("sph").get<double>();
  const json later = wait_for(c, id, [&](const json& s) {
    const json& fe_part = s.at("stage_wall_s").at("fe_check");
    return fe_part.is_number() && fe_part.get<double>() >= 0.5;
  });
  EXPECT_GE(later.at("wall_s").get<double>(), sph_wall + 0.5) << later.dump();
  EXPECT_LT(later.at("progress").get<int>(), 100);
  // The stage's progress events go on while a tool runs (it reports only between meshes).
  bool fe_progress = false;
  c.events("/jobs/" + id + "/events", [&](const SseEvent& e) {
    const json d = json::parse(e.data);
    fe_progress = e.event == "progress" && d.value("stage", "") == "fe_check" &&
                  d.at("fe_check").at("wall_s").get<double>() >= 0.5;
    return !fe_progress;
  });
  std::ofstream(go) << "go\n";

  // The SPH result stands; the failed check is in the status, the message and the events.
  const json final = wait_final(c, id, std::chrono::seconds(120));
  ASSERT_EQ(final.at("status"), "successful") << final.dump();
  EXPECT_EQ(final.at("progress"), 100);
  const json& check = final.at("fe_check");
  EXPECT_EQ(check.at("status"), "failed") << final.dump();
  EXPECT_NE(check.at("message").get<std::string>().find("gmsh"), std::string::npos) << check.dump();
  EXPECT_NE(final.at("message").get<std::string>().find("the FE check failed"), std::string::npos)
      << final.dump();
  const double fe_wall = final.at("stage_wall_s").at("fe_check").get<double>();
  EXPECT_GE(fe_wall, 0.5);
  EXPECT_NEAR(final.at("wall_s").get<double>(),
              final.at("stage_wall_s").at("sph").get<double>() + fe_wall, 1e-6);
  // The list says the same.
  const json list = c.get("/jobs").json();
  bool listed = false;
  for (const json& j : list.at("jobs")) {
    if (j.at("jobID").get<std::string>() != id) continue;
    listed = true;
    EXPECT_EQ(j.at("fe_check").at("status"), "failed");
  }
  EXPECT_TRUE(listed) << list.dump();
  bool failed_status = false;
  c.events("/jobs/" + id + "/events", [&](const SseEvent& e) {
    const json d = json::parse(e.data);
    failed_status = failed_status || (e.event == "status" && d.at("fe_check").is_object() &&
                                      d.at("fe_check").at("status") == "failed");
    return true;
  });
  EXPECT_TRUE(fe_progress);
  EXPECT_TRUE(failed_status);
}

TEST(ServerFe, TheWorkerRunsTheCheckAfterTheRun) {
  if (const std::string why = fe::fe_unavailable_reason(); !why.empty()) GTEST_SKIP() << why;
  ServerProcess server({"--threads-per-job", "1"});
  auto c = server.client();
  const std::string id = submit(c, static_gear_job(2e-4));  // a short relaxation will do
  ASSERT_FALSE(id.empty());
  const json status = wait_final(c, id, std::chrono::seconds(300));
  ASSERT_EQ(status.at("status"), "successful") << status.dump();
  const ClientResponse res = c.get("/jobs/" + id + "/results");
  ASSERT_EQ(res.status, 200u);
  const json results = res.json();
  ASSERT_TRUE(results.at("summary").contains("fe_comparison")) << results.dump();
  const json& block = results.at("summary").at("fe_comparison");
  EXPECT_TRUE(block.at("status") == "compared" || block.at("status") == "sph_values_missing")
      << block.dump();
  const double fe = block.at("fillet_tension_peak_Pa").at("fe").get<double>();
  EXPECT_TRUE(fe > 0.0 && fe < 1e10) << fe;
  std::set<std::string> names;
  for (const json& f : results.at("files")) names.insert(f.at("name").get<std::string>());
  for (const char* n : {"fe_summary.json", "fe_fillet_curves.csv", "fe_fillet_curves.json"}) {
    EXPECT_TRUE(names.count(n)) << n;
  }
}

}  // namespace
}  // namespace gearsph::server::testing
