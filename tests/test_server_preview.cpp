// POST /preview over real HTTP: the scene a job would build (bodies,
// outlines, modelled teeth, particles, steps) and the run-time estimate,
// the same refusals as POST /jobs, and nothing stored.
#include <cmath>
#include <thread>

#include "tests/test_server_support.hpp"

namespace gearsph::server::testing {
namespace {

const json kPaperCase = {{"scene", {{"type", "rack_pinion"}}}};

class ServerPreview : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { server_ = new ServerProcess({"--threads-per-job", "1"}); }
  static void TearDownTestSuite() {
    delete server_;
    server_ = nullptr;
  }
  static ServerProcess* server_;
};
ServerProcess* ServerPreview::server_ = nullptr;

TEST_F(ServerPreview, PaperCaseGeometryAgreesWithSubmission) {
  auto c = server_->client();
  const ClientResponse r = c.post_json("/preview", kPaperCase.dump());
  ASSERT_EQ(r.status, 200u) << r.body;
  EXPECT_EQ(r.header("Content-Type"), "application/json");
  const json p = r.json();
  EXPECT_EQ(p.at("scene"), "rack_pinion");
  EXPECT_TRUE(p.at("accepted").get<bool>());
  EXPECT_TRUE(p.at("errors").empty());

  // Bodies: pinion and rack, their counts adding up to the total.
  ASSERT_EQ(p.at("bodies").size(), 2u);
  EXPECT_EQ(p.at("bodies")[0].at("name"), "pinion");
  EXPECT_EQ(p.at("bodies")[1].at("name"), "rack");
  std::int64_t sum = 0;
  for (const json& b : p.at("bodies")) {
    EXPECT_EQ(b.at("free").get<std::int64_t>() + b.at("driven").get<std::int64_t>(),
              b.at("particles").get<std::int64_t>());
    EXPECT_GT(b.at("driven").get<std::int64_t>(), 0);  // hub ring, guided rack back
    EXPECT_DOUBLE_EQ(b.at("E_Pa").get<double>(), 1.73e11);
    sum += b.at("particles").get<std::int64_t>();
  }
  const auto n = p.at("particles").get<std::int64_t>();
  EXPECT_EQ(sum, n);
  EXPECT_GT(n, 100);

  // The particles themselves, one entry each, inside the bounds.
  const json& pts = p.at("points");
  ASSERT_TRUE(pts.is_object());
  for (const char* k : {"x", "y", "body", "driven"}) {
    EXPECT_EQ(pts.at(k).size(), static_cast<std::size_t>(n)) << k;
  }
  const json& bounds = p.at("bounds_m");
  for (std::size_t i = 0; i < pts.at("x").size(); ++i) {
    const double x = pts.at("x")[i], y = pts.at("y")[i];
    ASSERT_TRUE(x >= bounds[0].get<double>() - 1e-6 && x <= bounds[2].get<double>() + 1e-6);
    ASSERT_TRUE(y >= bounds[1].get<double>() - 1e-6 && y <= bounds[3].get<double>() + 1e-6);
  }

  // Outlines of both bodies, and the modelled teeth the scene chose.
  std::set<std::string> outlined;
  for (const json& o : p.at("outlines")) {
    EXPECT_GE(o.at("points").size(), 3u);
    if (o.at("body").is_string()) outlined.insert(o.at("body").get<std::string>());
  }
  EXPECT_TRUE(outlined.count("pinion") && outlined.count("rack")) << p.at("outlines").dump();
  EXPECT_FALSE(p.at("model").at("pinion").at("modelled_teeth").empty());
  EXPECT_GT(p.at("model").at("rack").at("modelled_teeth").get<int>(), 0);

  // The seed paper's time span; body-fitted particles take the automatic
  // step, 80 % of the stable limit.
  EXPECT_DOUBLE_EQ(p.at("end_s").get<double>(), 0.04);
  EXPECT_NEAR(p.at("dt_s").get<double>(), 0.8 * p.at("dt_limit_s").get<double>(), 1e-20);
  const auto steps = p.at("steps").get<std::int64_t>();
  EXPECT_EQ(steps, std::llround(std::ceil(0.04 / p.at("dt_s").get<double>() - 1e-9)));
  EXPECT_DOUBLE_EQ(p.at("particle_steps").get<double>(), double(n) * double(steps));
  EXPECT_EQ(p.at("job").at("scene").at("pinion").at("teeth"), 12);

  // The same counts as the server's admission of the same job.
  const ClientResponse s = c.post_json("/jobs", kPaperCase.dump());
  ASSERT_EQ(s.status, 201u) << s.body;
  EXPECT_EQ(s.json().at("particles").get<std::int64_t>(), n);
  EXPECT_EQ(s.json().at("steps").get<std::int64_t>(), steps);
  EXPECT_EQ(c.request("DELETE", "/jobs/" + s.json().at("jobID").get<std::string>()).status, 200u);
}

TEST_F(ServerPreview, ParametersChangeTheGeometry) {
  auto c = server_->client();
  // On the seed paper's lattice a larger pinion at half the spacing has more than
  // three times the particles (body-fitted particles keep the fillets' own
  // spacing, so the rim's spacing moves their count less).
  json paper_lattice = kPaperCase;
  paper_lattice["discretization"] = {{"particles", "lattice"}};
  json bigger = kPaperCase;
  bigger["scene"]["pinion"] = {{"teeth", 20}};
  bigger["discretization"] = {{"spacing_mm", 0.5}, {"particles", "lattice"}};
  const json a = c.post_json("/preview", paper_lattice.dump()).json();
  const ClientResponse r = c.post_json("/preview", bigger.dump());
  ASSERT_EQ(r.status, 200u) << r.body;
  const json b = r.json();
  EXPECT_DOUBLE_EQ(b.at("spacing_m").get<double>(), 0.5e-3);
  EXPECT_DOUBLE_EQ(b.at("model").at("pinion").at("pitch_radius_m").get<double>(), 0.04);
  EXPECT_GT(b.at("particles").get<std::int64_t>(), 3 * a.at("particles").get<std::int64_t>());

  json bigger_fitted = kPaperCase;
  bigger_fitted["scene"]["pinion"] = {{"teeth", 20}};
  const json fa = c.post_json("/preview", kPaperCase.dump()).json();
  const json fb = c.post_json("/preview", bigger_fitted.dump()).json();
  EXPECT_GT(fb.at("particles").get<std::int64_t>(), fa.at("particles").get<std::int64_t>());
}

// A server without a finished job measures its own speed (the paper's case
// for a few thousand steps) instead of quoting a constant: 5e4
// particle-steps per second put the paper's one-minute case at 8 h.
TEST_F(ServerPreview, CalibratedEstimateOnAServerWithoutFinishedJobs) {
  ServerProcess fresh({"--threads-per-job", "1"});
  auto c = fresh.client(std::chrono::seconds(120));
  const json p = c.post_json("/preview", kPaperCase.dump()).json();
  const json& rt = p.at("run_time");
  EXPECT_EQ(rt.at("basis"), "calibrated") << rt.dump();
  EXPECT_EQ(rt.at("jobs_measured"), 0);
  const double speed = rt.at("particle_steps_per_s").get<double>();
  // Any machine this runs on computes faster than 1e5 particle-steps a
  // second on one thread (1-3e7 measured on 2 cores).
  EXPECT_GT(speed, 1e5);
  EXPECT_NEAR(rt.at("compute_s").get<double>(), p.at("particle_steps").get<double>() / speed,
              1e-9 * rt.at("compute_s").get<double>());
  // Writing the frames and histories comes on top (test_server_hardening.cpp).
  EXPECT_GT(rt.at("output_s").get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(rt.at("wall_s").get<double>(),
                   rt.at("compute_s").get<double>() + rt.at("output_s").get<double>());
  EXPECT_NE(rt.at("note").get<std::string>().find("estimate"), std::string::npos);
  // A preview stores nothing.
  EXPECT_EQ(c.get("/jobs").json().at("jobs").size(), 0u);
}

TEST_F(ServerPreview, EstimateFromFinishedJobs) {
  ServerProcess fresh({"--threads-per-job", "1"});
  auto c = fresh.client();
  json job = kPaperCase;
  job["time"] = {{"end_s", 2e-5}};
  job["output"] = {{"frames", 2}};
  const std::string id = submit(c, job);
  ASSERT_FALSE(id.empty());
  const json done = wait_final(c, id, std::chrono::seconds(600));
  ASSERT_EQ(done.at("status"), "successful") << done.dump();
  const json rt = c.post_json("/preview", kPaperCase.dump()).json().at("run_time");
  const double wall = done.at("wall_s").get<double>();
  if (wall >= 1.0) {
    // The job's own speed: particles x steps over its wall time, less the
    // estimated time it spent writing its output (at most 90 % of it).
    const double speed = done.at("particles").get<double>() * done.at("steps").get<double>() / wall;
    EXPECT_EQ(rt.at("basis"), "measured");
    EXPECT_EQ(rt.at("jobs_measured"), 1);
    EXPECT_GE(rt.at("particle_steps_per_s").get<double>(), speed * (1 - 1e-9));
    EXPECT_LE(rt.at("particle_steps_per_s").get<double>(), 10 * speed * (1 + 1e-9));
  } else {
    // Too short to measure a speed from (mostly start-up): the calibration's.
    EXPECT_EQ(rt.at("basis"), "calibrated");
  }
}

TEST_F(ServerPreview, InvalidJobsGetTheirProblemsAtTheFields) {
  auto c = server_->client();
  json bad = kPaperCase;
  bad["scene"]["pinion"] = {{"teeth", 3}, {"module_mm", -1}};
  // The preview answers (200) with the problems; POST /jobs refuses (400)
  // with the same pointers.
  const ClientResponse r = c.post_json("/preview", bad.dump());
  ASSERT_EQ(r.status, 200u) << r.body;
  const json p = r.json();
  EXPECT_FALSE(p.at("valid").get<bool>());
  EXPECT_FALSE(p.at("accepted").get<bool>());
  EXPECT_EQ(p.at("type"), "urn:gearsph:problem:invalid-job");
  EXPECT_FALSE(p.contains("outlines"));
  std::set<std::string> pointers;
  for (const json& e : p.at("errors")) {
    pointers.insert(e.at("pointer").get<std::string>());
    EXPECT_FALSE(e.at("detail").get<std::string>().empty());
  }
  EXPECT_TRUE(pointers.count("/scene/pinion/teeth")) << r.body;
  EXPECT_TRUE(pointers.count("/scene/pinion/module_mm")) << r.body;

  const ClientResponse s = c.post_json("/jobs", bad.dump());
  ASSERT_EQ(s.status, 400u) << s.body;
  std::set<std::string> refused;
  const json refusal = s.json();  // kept: a loop over a temporary's member would dangle
  for (const json& e : refusal.at("errors")) refused.insert(e.at("pointer").get<std::string>());
  EXPECT_EQ(refused, pointers);

  // Requests that are not a JSON job at all are errors.
  EXPECT_EQ(c.post_json("/preview", "{\"scene\": ").status, 400u);
  EXPECT_EQ(c.request("POST", "/preview", "{}", {{"Content-Type", "text/plain"}}).status, 415u);
  EXPECT_EQ(c.get("/preview").status, 405u);
}

TEST_F(ServerPreview, FarTooManyParticlesAreRefusedBeforeBuilding) {
  auto c = server_->client();
  json huge = kPaperCase;
  huge["discretization"] = {{"spacing_mm", 0.001}};
  const ClientResponse r = c.post_json("/preview", huge.dump());
  ASSERT_EQ(r.status, 200u) << r.body;
  const json p = r.json();
  EXPECT_TRUE(p.at("valid").get<bool>());
  EXPECT_FALSE(p.at("accepted").get<bool>());
  EXPECT_EQ(p.at("errors")[0].at("pointer"), "/discretization");
  EXPECT_GT(p.at("estimate").at("particles").get<double>(), 5e6);
  EXPECT_FALSE(p.at("estimate").at("exact").get<bool>());
  EXPECT_FALSE(p.contains("outlines"));
}

// A plate of 200 x 20 mm with its 50 mm clamp on a 0.05 mm lattice:
// (4000 + 1000) x 400 = 2,000,000 particles (66 s and 2.3 GB to build).
json plate_at(double spacing_mm) {
  return {{"scene", {{"type", "plate"}, {"length_m", 0.2}, {"thickness_m", 0.02}}},
          {"discretization", {{"spacing_mm", spacing_mm}}}};
}
double plate_particles(double spacing_mm) {
  const auto cells = [&](double mm) { return double(std::lround(mm / spacing_mm)); };
  return (cells(200) + cells(50)) * cells(20);
}

// N1: a 2-million-particle preview is answered from the solver's estimate
// without building the scene, while a small one beside it is served.
TEST_F(ServerPreview, TwoMillionParticlesAreEstimatedNotBuilt) {
  ASSERT_DOUBLE_EQ(plate_particles(0.05), 2e6);
  json small_answer;
  std::thread small([&] {
    auto c = server_->client();
    const ClientResponse r = c.post_json("/preview", plate_at(2.0).dump());
    ASSERT_EQ(r.status, 200u) << r.body;
    small_answer = r.json();
  });
  auto c = server_->client();
  const ClientResponse r = c.post_json("/preview", plate_at(0.05).dump());
  small.join();
  ASSERT_EQ(r.status, 200u) << r.body;
  const json p = r.json();
  EXPECT_FALSE(p.at("built").get<bool>());
  EXPECT_TRUE(p.at("points").is_null());
  EXPECT_FALSE(p.contains("outlines"));
  EXPECT_FALSE(p.at("estimate").at("exact").get<bool>());
  EXPECT_NEAR(p.at("particles").get<double>(), 2e6, 0.05 * 2e6);
  // 1.2e12 particle-steps: over this server's 1e12, said at the field.
  EXPECT_FALSE(p.at("accepted").get<bool>());
  EXPECT_EQ(p.at("errors")[0].at("pointer"), "/time/end_s");
  // The small plate is built: its particles listed, counted exactly.
  EXPECT_TRUE(small_answer.at("built").get<bool>());
  EXPECT_EQ(small_answer.at("particles").get<double>(), plate_particles(2.0));
  EXPECT_EQ(small_answer.at("points").at("x").size(), std::size_t(plate_particles(2.0)));
}

// The estimate against counts one can derive (lattice) or build (the
// paper's gears at 0.5 mm, body-fitted and graded).
TEST(ServerAdmission, EstimatesAgreeWithTheBuiltCounts) {
  ServerProcess estimating({"--threads-per-job", "1", "--build-budget", "1"});
  ServerProcess building({"--threads-per-job", "1", "--build-budget", "1e6"});
  auto e = estimating.client(std::chrono::seconds(120));
  auto b = building.client(std::chrono::seconds(120));
  for (double mm : {0.5, 0.1}) {
    const json p = e.post_json("/preview", plate_at(mm).dump()).json();
    ASSERT_FALSE(p.at("built").get<bool>()) << mm;
    EXPECT_NEAR(p.at("particles").get<double>(), plate_particles(mm), 0.05 * plate_particles(mm));
  }
  json gears = kPaperCase;
  gears["discretization"] = {{"spacing_mm", 0.5}};
  const json est = e.post_json("/preview", gears.dump()).json();
  const json built = b.post_json("/preview", gears.dump()).json();
  ASSERT_FALSE(est.at("built").get<bool>()) << est.dump();
  ASSERT_TRUE(built.at("built").get<bool>()) << built.dump();
  EXPECT_TRUE(est.at("estimate").at("body_fitted").get<bool>());
  const double n = built.at("particles").get<double>(), steps = built.at("steps").get<double>();
  EXPECT_NEAR(est.at("particles").get<double>(), n, 0.05 * n);
  EXPECT_NEAR(est.at("steps").get<double>(), steps, 0.1 * steps);
}

// N1: a preview whose client hangs up stops building (the paper's gears at
// 0.5 mm take some 7 s to build); the next request is served.
TEST(ServerAdmission, AnAbandonedPreviewStopsBuilding) {
  ServerProcess server({"--threads-per-job", "1", "--build-budget", "1e6"});
  json gears = kPaperCase;
  gears["discretization"] = {{"spacing_mm", 0.5}};
  const std::string body = gears.dump();
  const std::string request =
      "POST /preview HTTP/1.1\r\nHost: 127.0.0.1:" + server.port() +
      "\r\nContent-Type: application/json\r\nContent-Length: " + std::to_string(body.size()) +
      "\r\n\r\n" + body;
  // Sent, and the connection closed at once.
  raw_exchange(server.host(), server.port(), request, std::chrono::milliseconds(200));
  bool stopped = false;
  for (int i = 0; i < 600 && !stopped; ++i) {
    stopped =
        server.log().find("POST /preview: stopped: the request was abandoned") != std::string::npos;
    if (!stopped) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_TRUE(stopped) << server.log();
  EXPECT_EQ(server.client().get("/health").status, 200u);
}

// A submission beyond the build budget is stored with the estimate's
// counts, not built in the request; the same preview twice is served
// from the cache.
TEST(ServerAdmission, SubmissionsBeyondTheBudgetAreNotBuiltAndPreviewsAreCached) {
  ServerProcess server({"--no-local-workers", "--build-budget", "1000"});
  auto c = server.client();
  const ClientResponse r = c.post_json("/jobs", plate_at(0.5).dump());
  ASSERT_EQ(r.status, 201u) << r.body;
  const json job = c.get(r.header("Location")).json();
  EXPECT_NEAR(job.at("particles").get<double>(), plate_particles(0.5), 0.05 * plate_particles(0.5))
      << job.dump();
  const json first = c.post_json("/preview", plate_at(0.5).dump()).json();
  const json second = c.post_json("/preview", plate_at(0.5).dump()).json();
  EXPECT_FALSE(first.at("cached").get<bool>());
  EXPECT_TRUE(second.at("cached").get<bool>());
  EXPECT_EQ(first.at("particles"), second.at("particles"));
  EXPECT_TRUE(second.contains("run_time"));
  // Over the limits: 422 at once, with the estimate and the limits.
  ServerProcess strict({"--no-local-workers", "--max-particles", "10000"});
  auto s = strict.client();
  const ClientResponse big = s.post_json("/jobs", plate_at(0.05).dump());
  ASSERT_EQ(big.status, 422u) << big.body;
  const json problem = big.json();
  EXPECT_EQ(problem.at("limits").at("particles"), 10000);
  EXPECT_GT(problem.at("estimate").at("particles").get<double>(), 1e6);
  EXPECT_EQ(problem.at("errors")[0].at("pointer"), "/discretization");
}

TEST_F(ServerPreview, JobsOverTheLimitsShowGeometryAndSayWhy) {
  ServerProcess small({"--threads-per-job", "1", "--max-steps", "1000"});
  auto c = small.client();
  const ClientResponse r = c.post_json("/preview", kPaperCase.dump());
  ASSERT_EQ(r.status, 200u) << r.body;
  const json p = r.json();
  EXPECT_FALSE(p.at("accepted").get<bool>());
  ASSERT_FALSE(p.at("errors").empty());
  EXPECT_EQ(p.at("errors")[0].at("pointer"), "/time/end_s") << p.at("errors").dump();
  EXPECT_FALSE(p.at("outlines").empty());
  EXPECT_EQ(p.at("limits").at("steps"), 1000);
  // POST /jobs refuses the same job.
  EXPECT_EQ(c.post_json("/jobs", kPaperCase.dump()).status, 422u);
}

}  // namespace
}  // namespace gearsph::server::testing
