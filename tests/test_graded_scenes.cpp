// The validation scenes' body-fitted, graded variants (docs/validation.md,
// "Graded twins"): particles that fill each body's true area, graded 4:1 from
// the scene's stress raiser, the same every time; and the scenes that cannot
// place them say so instead of placing a lattice.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "solver/job/job.hpp"
#include "tests/support/job_issues.hpp"

namespace gearsph {
namespace {

using nlohmann::json;

struct GradedScene {
  const char* name;
  json scene;
  double spacing;
  double area;  // of all bodies, m^2 per unit thickness
  double rho;
};

std::vector<GradedScene> graded_scenes() {
  return {
      {"plate",
       {{"type", "plate"}, {"length_m", 0.2}, {"thickness_m", 0.02}, {"Vf", 0.01}},
       0.002,
       0.25 * 0.02,  // the clamp (L/4) belongs to the plate
       1000.0},
      {"strip",
       {{"type", "strip_wave"}, {"length_m", 0.3}, {"thickness_m", 0.006}, {"lateral", "free"}},
       0.001,
       0.3 * 0.006,
       7800.0},
      {"disk",
       {{"type", "spinning_disk"}, {"radius_m", 0.02}, {"omega_rad_s", 2000.0}},
       0.002,
       std::numbers::pi * 0.02 * 0.02,
       7800.0},
      {"bar", {{"type", "bar_impact"}, {"length_m", 0.05}}, 0.001, 2 * 0.05 * 0.01, 7800.0},
  };
}

json graded_job(const GradedScene& g) {
  return {{"scene", g.scene},
          {"discretization",
           {{"particles", "body_fitted"},
            {"spacing_m", g.spacing},
            {"fine_spacing_m", 0.25 * g.spacing}}}};
}

TEST(GradedScenes, FillTheTrueAreaGradedFourToOneAndTheSameEveryTime) {
  for (const GradedScene& g : graded_scenes()) {
    SCOPED_TRACE(g.name);
    const PreparedJob job = prepare_job(graded_job(g), 1);
    const Particles& p = job.scene.sim.particles;
    double mass = 0.0;
    for (std::size_t i = 0; i < p.n; ++i) mass += p.mass[i];
    // Voronoi volumes clipped to the outline: the area within 0.1 %.
    EXPECT_NEAR(mass / (g.rho * g.area), 1.0, 1e-3);
    const auto [finest, coarsest] = std::minmax_element(p.spacing.begin(), p.spacing.end());
    // Never finer than asked; at least 3.8:1 between the finest particle
    // (a fraction of a spacing off the feature) and the bulk.
    EXPECT_GE(*finest, 0.25 * g.spacing * (1.0 - 1e-9));
    EXPECT_GE(*coarsest / *finest, 3.8);
    EXPECT_NEAR(*coarsest, g.spacing, 1e-3 * g.spacing);
    EXPECT_EQ(job.scene.description.at("particles"), "body_fitted");
    const PreparedJob again = prepare_job(graded_job(g), 1);
    ASSERT_EQ(again.scene.sim.particles.n, p.n);
    for (std::size_t i = 0; i < p.n; ++i) {
      ASSERT_EQ(again.scene.sim.particles.x[i], p.x[i]);
      ASSERT_EQ(again.scene.sim.particles.y[i], p.y[i]);
    }
  }
}

// The fine spacing sits where the scene says: a particle at the feature is
// fine, one a bulk spacing's growth distance from it is coarse.
TEST(GradedScenes, TheFineSpacingSitsAtEachScenesStressRaiser) {
  const std::vector<GradedScene> all = graded_scenes();
  auto spacing_near = [](const Particles& p, double x, double y) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < p.n; ++i) {
      if (std::hypot(p.x[i] - x, p.y[i] - y) < std::hypot(p.x[best] - x, p.y[best] - y)) best = i;
    }
    return p.spacing[best];
  };
  const PreparedJob plate = prepare_job(graded_job(all[0]), 1);
  EXPECT_LT(spacing_near(plate.scene.sim.particles, 0.0, 0.0), 0.3 * 0.002);    // clamp face
  EXPECT_GT(spacing_near(plate.scene.sim.particles, 0.19, 0.0), 0.95 * 0.002);  // tip
  const PreparedJob disk = prepare_job(graded_job(all[2]), 1);
  EXPECT_LT(spacing_near(disk.scene.sim.particles, 0.0, 0.0), 0.3 * 0.002);     // centre
  EXPECT_GT(spacing_near(disk.scene.sim.particles, 0.0, 0.019), 0.95 * 0.002);  // rim
  const PreparedJob bar = prepare_job(graded_job(all[3]), 1);
  EXPECT_LT(spacing_near(bar.scene.sim.particles, 0.0, 0.0), 0.3 * 0.001);     // facing ends
  EXPECT_GT(spacing_near(bar.scene.sim.particles, -0.04, 0.0), 0.95 * 0.001);  // far end
}

using testing_support::issues_of;

TEST(GradedScenes, ScenesWithoutBodyFittedParticlesRefuseThemByName) {
  const auto grips = issues_of(
      {{"scene", {{"type", "tension_strip"}}}, {"discretization", {{"particles", "body_fitted"}}}});
  ASSERT_EQ(grips.size(), 1u);
  EXPECT_EQ(grips[0].pointer, "/discretization/particles");
  const auto confined = issues_of({{"scene", {{"type", "strip_wave"}, {"lateral", "confined"}}},
                                   {"discretization", {{"particles", "body_fitted"}}}});
  ASSERT_EQ(confined.size(), 1u);
  EXPECT_EQ(confined[0].pointer, "/discretization/particles");
  EXPECT_NE(confined[0].message.find("free"), std::string::npos) << confined[0].message;
}

}  // namespace
}  // namespace gearsph
