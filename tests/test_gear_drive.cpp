// The pinion driven by a torque (issue 3, kinematics): the hub is a rigid
// body turned by the applied torque and the teeth's moment, with the whole
// gear's inertia. Checked against Newton's law for a free spin-up; the
// balanced static case is in validation_gear_drive.cpp (a minute long).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/geometry/polygon.hpp"
#include "solver/job/job.hpp"
#include "solver/run/runner.hpp"

namespace gearsph {
namespace {

using nlohmann::json;
constexpr double kPi = std::numbers::pi;

TEST(PolarMoment, MatchesCircleAndRectangle) {
  const double radius = 0.03;
  geometry::Polygon circle;
  for (int k = 0; k < 4000; ++k) {
    const double a = 2 * kPi * k / 4000;
    circle.push_back({radius * std::cos(a), radius * std::sin(a)});
  }
  const double disk = 0.5 * kPi * std::pow(radius, 4);  // pi r^4 / 2
  EXPECT_NEAR(geometry::polar_moment(circle), disk, 1e-5 * disk);
  // A w x h rectangle with a corner at the origin: (w h / 3)(w^2 + h^2).
  const double w = 0.2, h = 0.05;
  const geometry::Polygon rect{{0, 0}, {w, 0}, {w, h}, {0, h}};
  EXPECT_NEAR(geometry::polar_moment(rect), w * h * (w * w + h * h) / 3.0, 1e-15);
}

json gear_job(json pinion, json rack, double end_s) {
  json job = {{"name", "torque-drive"},
              {"scene",
               {{"type", "rack_pinion"},
                {"pinion", std::move(pinion)},
                {"rack", std::move(rack)},
                {"mesh_phase", "centred"}}},
              {"time", {{"end_s", end_s}}},
              {"output", {{"history_points", 100}, {"frames", 0}}}};
  return job;
}

TEST(TorqueDrive, SpinsUpTheWholeGearByNewtonsLaw) {
  // At rest, the play shared (0.05 mm each side): the teeth touch after the
  // hub turns 2e-3 rad, at about 0.2 ms under this torque. Over 0.1 ms the
  // gear turns freely: omega = T t / I with I the whole gear's inertia.
  const double torque = -10.0, end = 1e-4;
  PreparedJob job = prepare_job(
      gear_job({{"omega_rad_s", 0.0}, {"torque_N_m", torque}}, {{"velocity_m_s", 0.0}}, end));
  const RunResult r = run_job(job);
  ASSERT_EQ(r.status, "completed") << r.message;
  const json& drive = r.summary.at("model").at("pinion").at("drive");
  const double inertia = drive.at("pinion_inertia_kg_m2").get<double>();
  // Bounded by solid disks of the root and tip radii (b = 20 mm, steel 7800).
  const json& pinion = r.summary.at("model").at("pinion");
  auto disk = [](double radius) { return 0.5 * kPi * 7800 * 0.02 * std::pow(radius, 4); };
  EXPECT_GT(inertia, disk(pinion.at("root_radius_m").get<double>()));
  EXPECT_LT(inertia, disk(pinion.at("tip_radius_m").get<double>()));
  const History& h = r.history;
  const double omega = h.at(h.rows() - 1, static_cast<std::size_t>(h.index("pinion_omega_rad_s")));
  const double expected = torque * end / inertia;
  // The teeth follow the hub through their elasticity (transit ~2 us), so
  // they lag by a small oscillation about the rigid motion.
  EXPECT_NEAR(omega, expected, 0.01 * std::abs(expected));
  EXPECT_EQ(r.summary.at("max_contact_force_N").get<double>(), 0.0);
}

}  // namespace
}  // namespace gearsph
