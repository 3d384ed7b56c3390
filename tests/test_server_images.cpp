// GET /jobs/{id}/images/{field}.png over real HTTP, in a build with the
// renderer (without it the endpoint answers 501, see test_server_api.cpp):
// every frame, including the initial state whose stress is zero everywhere,
// the fields, the zoom window, the colour range, the refusals, and the
// bounded cache.
#ifdef GEARSPH_WITH_RENDER

#include "tests/test_server_support.hpp"

namespace gearsph::server::testing {
namespace {

// Width and height from a PNG's IHDR chunk; {0, 0} if it is not a PNG.
std::pair<std::uint32_t, std::uint32_t> png_size(const std::string& png) {
  static const std::string signature = "\x89PNG\r\n\x1a\n";
  if (png.size() < 24 || png.compare(0, 8, signature) != 0 || png.compare(12, 4, "IHDR") != 0) {
    return {0, 0};
  }
  const auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(png[at + k]);
    return v;
  };
  return {be32(16), be32(20)};
}

class ServerImages : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    server_ = new ServerProcess({"--threads-per-job", "1", "--image-cache-mb", "0.3"});
    auto c = server_->client();
    json job = tiny_job();
    job["output"] = {{"frames", 4}};
    id_ = new std::string(submit(c, job));
    const json done = wait_final(c, *id_, std::chrono::seconds(300));
    ASSERT_EQ(done.at("status"), "successful") << done.dump();
  }
  static void TearDownTestSuite() {
    delete server_;
    delete id_;
    server_ = nullptr;
    id_ = nullptr;
  }
  static std::string image(const std::string& query) {
    return "/jobs/" + *id_ + "/images/" + query;
  }
  // Snapshots in results.h5, as results.xmf lists them.
  static int frame_count(HttpClient& c) {
    const std::string xmf = c.get("/jobs/" + *id_ + "/files/results.xmf").body;
    int n = 0;
    for (auto at = xmf.find("<Time Value="); at != std::string::npos;
         at = xmf.find("<Time Value=", at + 1)) {
      ++n;
    }
    return n;
  }
  static ServerProcess* server_;
  static std::string* id_;
};
ServerProcess* ServerImages::server_ = nullptr;
std::string* ServerImages::id_ = nullptr;

TEST_F(ServerImages, EveryFrameIncludingTheUnstressedInitialState) {
  auto c = server_->client(std::chrono::seconds(120));
  // Frame 0 is the initial state: von Mises stress zero everywhere.
  const ClientResponse first = c.get(image("von_mises.png?frame=0"));
  ASSERT_EQ(first.status, 200u) << first.body.substr(0, 300);
  EXPECT_EQ(first.header("Content-Type"), "image/png");
  EXPECT_EQ(png_size(first.body), std::make_pair(1280u, 800u));
  // Without a frame: the last one.
  const int frames = frame_count(c);
  ASSERT_GE(frames, 5);  // 4 requested, plus the initial state
  const ClientResponse last = c.get(image("von_mises.png"));
  ASSERT_EQ(last.status, 200u) << last.body.substr(0, 300);
  const ClientResponse final_frame =
      c.get(image("von_mises.png?frame=" + std::to_string(frames - 1)));
  ASSERT_EQ(final_frame.status, 200u) << final_frame.body.substr(0, 300);
  EXPECT_TRUE(last.body == final_frame.body);
  EXPECT_FALSE(first.body == last.body);
  for (const char* field :
       {"velocity", "displacement", "pressure", "stress_xy", "density", "body"}) {
    const ClientResponse r = c.get(image(std::string(field) + ".png?frame=0"));
    EXPECT_EQ(r.status, 200u) << field << ": " << r.body.substr(0, 300);
    EXPECT_EQ(png_size(r.body), std::make_pair(1280u, 800u)) << field;
  }
}

TEST_F(ServerImages, ZoomShowsAWindow) {
  auto c = server_->client(std::chrono::seconds(120));
  const ClientResponse whole = c.get(image("von_mises.png?frame=2"));
  const ClientResponse zoomed = c.get(image("von_mises.png?frame=2&zoom=0,0,0.02,0.01"));
  ASSERT_EQ(whole.status, 200u) << whole.body.substr(0, 300);
  ASSERT_EQ(zoomed.status, 200u) << zoomed.body.substr(0, 300);
  EXPECT_EQ(png_size(zoomed.body), std::make_pair(1280u, 800u));
  EXPECT_FALSE(whole.body == zoomed.body);
}

// The largest principal stress on a colour scale that the request fixes
// (the dashboard's SPH field beside the FE one): its own image per range.
TEST_F(ServerImages, LargestPrincipalStressOnAGivenRange) {
  auto c = server_->client(std::chrono::seconds(120));
  const ClientResponse own = c.get(image("max_principal.png?frame=2"));
  ASSERT_EQ(own.status, 200u) << own.body.substr(0, 300);
  EXPECT_EQ(own.header("Content-Type"), "image/png");
  EXPECT_EQ(png_size(own.body), std::make_pair(1280u, 800u));
  const auto health = [&] { return c.get("/health").json().at("image_cache"); };
  const int misses_before = health().at("misses").get<int>();
  const ClientResponse narrow = c.get(image("max_principal.png?frame=2&range=-1e5,1e5"));
  ASSERT_EQ(narrow.status, 200u) << narrow.body.substr(0, 300);
  EXPECT_EQ(png_size(narrow.body), std::make_pair(1280u, 800u));
  const ClientResponse wide = c.get(image("max_principal.png?frame=2&range=-1e9,1e9"));
  ASSERT_EQ(wide.status, 200u) << wide.body.substr(0, 300);
  // Each range rendered (a miss of the cache each), each its own picture.
  EXPECT_EQ(health().at("misses").get<int>(), misses_before + 2);
  EXPECT_FALSE(narrow.body == wide.body);
  EXPECT_FALSE(narrow.body == own.body);
  // The same range again: from the cache.
  const int hits_before = health().at("hits").get<int>();
  EXPECT_TRUE(c.get(image("max_principal.png?frame=2&range=-1e5,1e5")).body == narrow.body);
  EXPECT_EQ(health().at("hits").get<int>(), hits_before + 1);
  // A window about as tall as wide (a tooth) on the FE tooth figures' canvas.
  const ClientResponse tall =
      c.get(image("max_principal.png?frame=2&zoom=0,-0.01,0.01,0.0&range=-1e6,1e6"));
  ASSERT_EQ(tall.status, 200u) << tall.body.substr(0, 300);
  EXPECT_EQ(png_size(tall.body), std::make_pair(1100u, 1000u));
  // A range is two finite numbers, lo < hi, for a field with a colour scale.
  for (const char* bad : {"5,1", "a,b", "1", "1,1", "0,inf", "nan,1", "1,2,3", ""}) {
    const ClientResponse r = c.get(image(std::string("max_principal.png?range=") + bad));
    EXPECT_EQ(r.status, 400u) << bad;
    EXPECT_NE(r.json().at("detail").get<std::string>().find("lo < hi"), std::string::npos)
        << r.body;
  }
  const ClientResponse body = c.get(image("body.png?range=0,1"));
  EXPECT_EQ(body.status, 400u) << body.body.substr(0, 300);
}

TEST_F(ServerImages, RefusalsNameWhatExists) {
  auto c = server_->client(std::chrono::seconds(120));
  const int frames = frame_count(c);
  const ClientResponse past = c.get(image("von_mises.png?frame=" + std::to_string(frames)));
  EXPECT_EQ(past.status, 404u);
  EXPECT_NE(past.json().at("detail").get<std::string>().find("0 to " + std::to_string(frames - 1)),
            std::string::npos)
      << past.body;
  const ClientResponse unknown = c.get(image("temperature.png"));
  EXPECT_EQ(unknown.status, 400u);
  EXPECT_NE(unknown.json().at("detail").get<std::string>().find("von_mises"), std::string::npos)
      << unknown.body;
  EXPECT_EQ(c.get(image("von_mises.png?frame=x")).status, 400u);
  // A bad query parameter reads alike here and on the job list.
  const json bad_frame = c.get(image("von_mises.png?frame=x")).json();
  const json bad_limit = c.get("/jobs?limit=0").json();
  EXPECT_EQ(bad_frame.at("type"), bad_limit.at("type"));
  EXPECT_EQ(bad_frame.at("title"), "Invalid query parameter");
  EXPECT_EQ(bad_limit.at("title"), "Invalid query parameter");
  EXPECT_EQ(c.get(image("von_mises.png?zoom=1,1,0,0")).status, 400u);
  EXPECT_EQ(c.get(image("a..b.png")).status, 404u);
  EXPECT_EQ(c.get("/jobs/00000000-0000-0000-0000-000000000000/images/von_mises.png").status, 404u);
}

// Rendered images are kept in a bounded cache in memory, not in the job's
// directory: however many frames and zooms are asked for, its result files
// (what /results lists and `gearsph submit --out` downloads) stay the same.
TEST_F(ServerImages, RenderedImagesStayOutOfTheResultsInABoundedCache) {
  auto c = server_->client(std::chrono::seconds(120));
  const json files_before = c.get("/jobs/" + *id_ + "/files").json();
  const ClientResponse first = c.get(image("velocity.png?frame=1"));
  ASSERT_EQ(first.status, 200u) << first.body;
  EXPECT_EQ(first.header("Cache-Control"), "private, max-age=3600");
  // The second time from the cache: the same bytes, one hit more.
  const auto hits = [&] { return c.get("/health").json().at("image_cache").at("hits").get<int>(); };
  const int hits_before = hits();
  EXPECT_TRUE(c.get(image("velocity.png?frame=1")).body == first.body);
  EXPECT_EQ(hits(), hits_before + 1);
  // Many zoom windows: a 300 kB cache (--image-cache-mb 0.3) holds a few.
  for (int k = 1; k <= 12; ++k) {
    const std::string zoom = "0,0," + std::to_string(0.002 * k) + ",0.01";
    ASSERT_EQ(c.get(image("von_mises.png?frame=2&zoom=" + zoom)).status, 200u) << k;
  }
  const json cache = c.get("/health").json().at("image_cache");
  EXPECT_EQ(cache.at("max_bytes"), 300000);
  EXPECT_LE(cache.at("bytes").get<double>(), 3e5) << cache.dump();
  EXPECT_GT(cache.at("entries").get<int>(), 0) << cache.dump();
  // Fewer kept than rendered: the least recently used were dropped.
  EXPECT_LT(cache.at("entries").get<int>(), cache.at("misses").get<int>()) << cache.dump();
  // Nothing was written beside the results.
  EXPECT_EQ(c.get("/jobs/" + *id_ + "/files").json(), files_before);
  for (const auto& e : fs::directory_iterator(server_->data() / "jobs" / *id_)) {
    EXPECT_EQ(e.path().extension(), e.path().extension() == ".png" ? ".none" : e.path().extension())
        << "an image was written into the job directory: " << e.path();
  }
  std::set<std::string> listed;
  const json results = c.get("/jobs/" + *id_ + "/results").json();
  for (const json& f : results.at("files")) {
    listed.insert(f.at("name").get<std::string>());
  }
  for (const std::string& name : listed) EXPECT_EQ(name.rfind("image-", 0), std::string::npos);
}

}  // namespace
}  // namespace gearsph::server::testing

#endif  // GEARSPH_WITH_RENDER
