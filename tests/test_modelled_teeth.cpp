// The teeth a static check models (solver/scene/rack_pinion.cpp,
// static_check_pinion_teeth). It loads tooth 0 alone; its fillets sit in
// the rim beside its neighbours, so a job that asks for one or two teeth
// still gets tooth 0 with both neighbours, unloaded. One tooth alone read
// the fillet tension peak 8-25 % low against FE on three pinions
// (docs/gears.md, "One tooth means one loaded tooth"), and a rack count of
// one put the rack tooth beside tooth 0's other flank.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "solver/job/job.hpp"
#include "solver/run/runner.hpp"
#include "solver/scene/rack_pinion.hpp"

namespace gearsph {
namespace {

nlohmann::json static_check(const nlohmann::json& pinion_teeth, const nlohmann::json& rack_teeth,
                            double omega = 0.0) {
  return {{"scene",
           {{"type", "rack_pinion"},
            {"quasi_static", true},
            {"contact_point", "hpstc"},
            {"pinion", {{"omega_rad_s", omega}, {"modelled_teeth", pinion_teeth}}},
            {"rack", {{"velocity_m_s", 0}, {"load_N", 1000}, {"modelled_teeth", rack_teeth}}}}}};
}

// Every particle's body, place and mass.
std::vector<double> particle_state(const Scene& scene) {
  const Particles& p = scene.sim.particles;
  std::vector<double> out;
  for (std::size_t i = 0; i < p.n; ++i) {
    out.insert(out.end(), {p.x0[i], p.y0[i], p.mass[i], static_cast<double>(p.body[i])});
  }
  return out;
}

TEST(ModelledTeeth, AStaticCheckOfOneOrTwoTeethKeepsToothZerosNeighbours) {
  const PreparedJob reference = prepare_job(static_check("auto", "auto"), 1);
  EXPECT_EQ(reference.scene.description.at("pinion").at("modelled_teeth"),
            nlohmann::json({-1, 0, 1}));
  for (const int n : {1, 2}) {
    const PreparedJob job = prepare_job(static_check(n, "auto"), 1);
    const nlohmann::json& d = job.scene.description;
    EXPECT_EQ(d.at("pinion").at("modelled_teeth"), nlohmann::json({-1, 0, 1})) << n;
    EXPECT_EQ(particle_state(job.scene), particle_state(reference.scene)) << n;
    const std::string why = d.at("modelled_teeth_reason").get<std::string>();
    EXPECT_NE(why.find("neighbours are modelled too, unloaded"), std::string::npos) << why;
  }
}

TEST(ModelledTeeth, MoreTeethThanThreeAreTheJobsAndKeepTheNeighbours) {
  // Clockwise (omega <= 0) teeth come from +k: four teeth are -1..2.
  EXPECT_EQ(
      prepare_job(static_check(4, "auto"), 1).scene.description.at("pinion").at("modelled_teeth"),
      nlohmann::json({-1, 0, 1, 2}));
  // Counter-clockwise, from -k.
  EXPECT_EQ(scenes::static_check_pinion_teeth(
                validate_job(static_check(4, "auto", 1e-9))["scene"]["pinion"]),
            std::vector<int>({-2, -1, 0, 1}));
  // A 12-tooth pinion has no more than 12.
  EXPECT_EQ(
      scenes::static_check_pinion_teeth(validate_job(static_check(40, "auto"))["scene"]["pinion"])
          .size(),
      12u);
}

TEST(ModelledTeeth, AStaticCheckOfOneRackToothIsTheToothThatMeetsTheDrivingFlank) {
  const PreparedJob reference = prepare_job(static_check("auto", "auto"), 1);
  const PreparedJob one = prepare_job(static_check("auto", 1), 1);
  EXPECT_EQ(one.scene.description.at("rack").at("modelled_teeth"), 1);
  EXPECT_EQ(particle_state(one.scene), particle_state(reference.scene));
  // Two rack teeth: both sides of tooth 0, the driving one among them.
  EXPECT_EQ(
      prepare_job(static_check("auto", 2), 1).scene.description.at("rack").at("modelled_teeth"), 2);
}

// A static check whose tooth 0 carries less than half the load says so,
// instead of reporting zero fillet stresses as a completed check: here the
// run ends (2 us) long before the load ramp reaches the teeth.
TEST(ModelledTeeth, AStaticCheckWhoseToothZeroCarriesNoLoadWarns) {
  nlohmann::json j = static_check("auto", "auto");
  j["time"] = {{"end_s", 2e-6}};
  j["output"] = {{"frames", 0}};
  PreparedJob job = prepare_job(j, 1);
  const RunResult r = run_job(job);
  ASSERT_EQ(r.status, "completed") << r.message;
  const nlohmann::json& warnings = r.summary.at("warnings");
  ASSERT_EQ(warnings.size(), 1u) << warnings;
  EXPECT_NE(warnings[0].get<std::string>().find("tooth 0 carries 0 % of the rack load"),
            std::string::npos)
      << warnings;
}

}  // namespace
}  // namespace gearsph
