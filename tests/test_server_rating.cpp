// POST /rating over real HTTP: ISO/TR 6336-30 Example 1 answered at once
// with the same verdict as `gearsph rate`, and a bad rating refused with a
// problem naming each field.
#include <fstream>
#include <set>
#include <sstream>

#include "solver/gear/iso6336_rating.hpp"
#include "tests/test_server_support.hpp"

namespace gearsph::server::testing {
namespace {

json example_1() {
  std::ifstream f(std::string(GEARSPH_SOURCE_DIR) +
                  "/schemas/examples/rating-iso-tr-6336-30-1.json");
  std::stringstream s;
  s << f.rdbuf();
  return json::parse(s.str());
}

TEST(ServerRating, AnswersTheVerdictAtOnce) {
  ServerProcess server({"--threads-per-job", "1"});
  auto c = server.client();
  const ClientResponse r = c.post_json("/rating", example_1().dump());
  ASSERT_EQ(r.status, 200u) << r.body;
  const json verdict = r.json();
  EXPECT_EQ(verdict, gear::iso6336::rate_document(example_1()));
  EXPECT_NEAR(verdict.at("pitting").at("S_H")[0].get<double>(), 1.0285, 0.005 * 1.0285);

  json bad = example_1();
  bad["gears"][0]["teeth"] = 2;
  bad["load"].erase("speed_rpm");
  const ClientResponse refused = c.post_json("/rating", bad.dump());
  ASSERT_EQ(refused.status, 400u);
  EXPECT_EQ(refused.header("Content-Type"), "application/problem+json");
  const json problem = refused.json();
  std::set<std::string> pointers;
  for (const json& e : problem.at("errors")) {
    pointers.insert(e.at("pointer").get<std::string>());
    EXPECT_FALSE(e.at("detail").get<std::string>().empty());
  }
  EXPECT_TRUE(pointers.count("/gears/0/teeth"));
  EXPECT_TRUE(pointers.count("/load/speed_rpm")) << refused.body;
  EXPECT_EQ(c.post_json("/rating", "{not json").status, 400u);
}

}  // namespace
}  // namespace gearsph::server::testing
