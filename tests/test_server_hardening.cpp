// The job service against hostile and demanding use (issue 27): numbers
// beyond double, resumed event streams, the dashboard behind a token, the
// image cache, the Host header, dismissed runs, transfer codings, the
// run-time estimate, HTTP versions, store reads off the network threads and
// the OGC API - Processes document.
#include <fstream>
#include <thread>

#include "tests/test_server_support.hpp"

namespace gearsph::server::testing {
namespace {

// One server for the tests that do not need a fresh one.
class ServerHardening : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { server_ = new ServerProcess({"--threads-per-job", "1"}); }
  static void TearDownTestSuite() {
    expect_consistent_store(server_->data());
    delete server_;
    server_ = nullptr;
  }
  static ServerProcess* server_;
};
ServerProcess* ServerHardening::server_ = nullptr;

// 1. A number beyond the range of a double is valid JSON that no double can
// hold: 400 with the pointer to it, on every endpoint that takes a body.
TEST_F(ServerHardening, NumbersOutOfRangeAre400WithThePointer) {
  auto c = server_->client();
  for (const std::string& number :
       {std::string("1e400"), std::string("-1e400"), std::string(400, '9')}) {
    for (const char* path :
         {"/jobs", "/processes/gearsph-simulation/execution", "/preview", "/studies"}) {
      const ClientResponse r =
          c.post_json(path, R"({"name": "x", "time": {"end_s": )" + number + "}}");
      ASSERT_EQ(r.status, 400u) << path << " " << number << ": " << r.body;
      EXPECT_EQ(r.header("Content-Type"), "application/problem+json");
      const json p = r.json();
      EXPECT_EQ(p.at("type"), "urn:gearsph:problem:number-out-of-range") << r.body;
      ASSERT_EQ(p.at("errors").size(), 1u) << r.body;
      EXPECT_EQ(p.at("errors").at(0).at("pointer"), "/time/end_s") << r.body;
      EXPECT_NE(p.at("errors").at(0).at("detail").get<std::string>().find("out of range"),
                std::string::npos)
          << r.body;
    }
  }
  // In arrays, under the OGC wrapper, in a study's axes: the pointer is into the body.
  const ClientResponse wrapped = c.post_json(
      "/processes/gearsph-simulation/execution",
      R"({"inputs": {"job": {"scene": {"type": "rack_pinion", "rack": {"velocity_m_s": [0, -1e999]}}}}})");
  ASSERT_EQ(wrapped.status, 400u) << wrapped.body;
  EXPECT_EQ(wrapped.json().at("errors").at(0).at("pointer"),
            "/inputs/job/scene/rack/velocity_m_s/1");
  const ClientResponse study = c.post_json(
      "/studies",
      R"({"base": {"scene": {"type": "plate"}}, "axes": [{"pointer": "/time/end_s", "values": [0.1, 2e308]}]})");
  ASSERT_EQ(study.status, 400u) << study.body;
  EXPECT_EQ(study.json().at("errors").at(0).at("pointer"), "/axes/0/values/1");
  // Keys with '/' and '~' are escaped in the pointer (RFC 6901).
  const ClientResponse escaped = c.post_json("/preview", R"({"a/b~c": [1, {"d": 1e400}]})");
  ASSERT_EQ(escaped.status, 400u) << escaped.body;
  EXPECT_EQ(escaped.json().at("errors").at(0).at("pointer"), "/a~1b~0c/1/d");
  // Tiny numbers are no problem: they are zero, or close to it.
  EXPECT_EQ(
      c.post_json("/preview", R"({"scene": {"type": "plate"}, "time": {"end_s": 1e-400}})").status,
      200u);
  EXPECT_EQ(c.get("/health").status, 200u);
}

}  // namespace
}  // namespace gearsph::server::testing
