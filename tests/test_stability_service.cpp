// The health check through the job service: a job submitted with
// deliberately bad settings fails, and the job's status message names the
// detector, the step and the remedy (docs/stability.md).
// Built only with the service layer (its public compile definition).
#ifdef BOOST_BEAST_USE_STD_STRING_VIEW

#include "tests/test_server_support.hpp"

namespace gearsph::server::testing {
namespace {

TEST(StabilityService, DetectorMessageIsTheJobStatus) {
  ServerProcess server({"--workers", "1", "--threads-per-job", "1"});
  auto c = server.client();
  // Plain UL SPH with the cubic spline, pulled to 10 %: clumps at ~5 %.
  const json job = {{"scene",
                     {{"type", "tension_strip"},
                      {"length_m", 0.05},
                      {"thickness_m", 0.01},
                      {"peak_strain", 0.1}}},
                    {"discretization", {{"spacing_m", 0.001}, {"kernel", "cubic_spline"}}},
                    {"method",
                     {{"formulation", "updated_lagrangian"},
                      {"gradient_correction", "none"},
                      {"artificial_stress", {{"epsilon", 0.0}}}}},
                    {"output", {{"history_points", 200}, {"frames", 0}}}};
  const std::string id = submit(c, job);
  ASSERT_FALSE(id.empty());
  const json status = wait_final(c, id);
  ASSERT_EQ(status.at("status"), "failed") << status.dump(2);
  const std::string message = status.at("message").get<std::string>();
  EXPECT_NE(message.find("health check stopped the run (particle_disorder"), std::string::npos)
      << message;
  EXPECT_NE(message.find("particle disorder"), std::string::npos) << message;
  EXPECT_NE(message.find("artificial stress"), std::string::npos) << message;
}

}  // namespace
}  // namespace gearsph::server::testing

#endif
