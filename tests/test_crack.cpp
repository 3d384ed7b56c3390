// The crack's cut (geometry/crack.hpp, physics/crack_cut.hpp), the
// interaction integral on an exact Williams field
// (diagnostics/stress_intensity.hpp), and the cracked plate's refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/diagnostics/stress_intensity.hpp"
#include "solver/geometry/crack.hpp"
#include "solver/job/job.hpp"
#include "solver/physics/crack_growth.hpp"
#include "tests/support/job_issues.hpp"

namespace gearsph {
namespace {

using geometry::Crack;
using geometry::Point;

Crack vertical_crack() {
  return Crack{0, {{0.0, -1.0}, {0.0, 0.0}}, false};  // tip at the origin
}

TEST(Crack, CutsASegmentAcrossItsFacesOnly) {
  const Crack c = vertical_crack();
  EXPECT_TRUE(geometry::crack_cuts(c, {-0.1, -0.5}, {0.1, -0.4}));
  EXPECT_FALSE(geometry::crack_cuts(c, {-0.1, -0.5}, {-0.05, -0.4}));  // one side
  EXPECT_FALSE(geometry::crack_cuts(c, {-0.1, 0.1}, {0.1, 0.1}));      // ahead of the tip
  EXPECT_FALSE(geometry::crack_cuts(c, {-0.1, 0.0}, {0.1, 0.0}));      // through the tip
  EXPECT_TRUE(geometry::crack_cuts(c, {-0.1, -0.1}, {0.1, 0.05}));     // crosses below it
  EXPECT_FALSE(geometry::crack_cuts(c, {0.0, -0.5}, {0.1, -0.5}));     // a point on a face
}

TEST(Crack, CutsThroughAJointOnceAndNotPastAnInnerTip) {
  const Crack bent{0, {{0.0, -1.0}, {0.0, 0.0}, {1.0, 1.0}}, true};
  EXPECT_TRUE(geometry::crack_cuts(bent, {-0.1, 0.1}, {0.1, -0.1}));    // through the joint
  EXPECT_FALSE(geometry::crack_cuts(bent, {-0.1, -1.0}, {0.1, -1.0}));  // through the first tip
  EXPECT_TRUE(geometry::crack_cuts(bent, {0.5, 0.8}, {0.5, 0.2}));
}

// The cracked plate's reference pairs against the crack drawn by hand: an
// edge crack at x = 0 from the edge to y_tip cuts exactly the pairs that
// straddle x = 0 below the tip, and keeps those above it.
TEST(Crack, ReferencePairsStopAtTheFacesAndPassAheadOfTheTip) {
  const nlohmann::json job = {{"scene",
                               {{"type", "cracked_plate"},
                                {"width_m", 0.02},
                                {"length_m", 0.04},
                                {"crack", {{"kind", "edge"}, {"length_m", 0.005}}}}},
                              {"discretization", {{"spacing_m", 0.0005}}}};
  PreparedJob prepared = prepare_job(job, 1);
  const Simulation& sim = prepared.scene.sim;
  ASSERT_TRUE(sim.reference.built());
  const Particles& p = sim.particles;
  const double y_tip = -0.01 + 0.005;
  std::size_t across_ahead = 0;
  for (std::size_t i = 0; i < p.n; ++i) {
    for (std::uint32_t k = sim.reference.rows[i]; k < sim.reference.rows[i + 1]; ++k) {
      const std::size_t j = sim.reference.j[k];
      if (p.x0[i] * p.x0[j] >= 0.0) continue;
      const double t = -p.x0[i] / (p.x0[j] - p.x0[i]);
      const double y = p.y0[i] + t * (p.y0[j] - p.y0[i]);
      EXPECT_GE(y, y_tip - 1e-12) << "a pair across the faces at y = " << y;
      ++across_ahead;
    }
  }
  EXPECT_GT(across_ahead, 100u);  // the ligament is still bonded
}

// The integral takes back the K_I and K_II of an exact Williams field
// sampled at lattice points, with a T-stress on top (which it must ignore),
// for a tip whose crack runs at an angle to the axes.
TEST(StressIntensity, InteractionIntegralRecoversTheWilliamsFieldsFactors) {
  const double E = 2e11, nu = 0.3, K_I = 3e7, K_II = -1.2e7, T = 4e7;
  const double beta = 0.6, dx = 2e-4;
  const double c = std::cos(beta), s = std::sin(beta);
  const diagnostics::CrackTip tip{{0.001, -0.002}, {c, s}};
  const diagnostics::DomainRing ring{0.002, 0.006};
  std::vector<diagnostics::DomainPoint> points;
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  for (int a = -40; a < 40; ++a) {
    for (int b = -40; b < 40; ++b) {
      const double x1 = (a + 0.5) * dx, x2 = (b + 0.5) * dx;  // tip frame
      diagnostics::WilliamsField w = diagnostics::williams_field(K_I, K_II, x1, x2, E, nu);
      // T along the crack: strain eps11 = (1 - nu^2) T / E, eps22 = -nu (1 + nu) T / E.
      w.s11 += T;
      w.h11 += (1 - nu * nu) * T / E;
      w.h22 += -nu * (1 + nu) * T / E;
      // Tensors to global axes: T = Q^T T' Q, rows of Q e1 = (c, s), e2 = (-s, c).
      auto global = [&](double t11, double t12, double t21, double t22, double& xx, double& xy,
                        double& yx, double& yy) {
        xx = c * c * t11 - c * s * (t12 + t21) + s * s * t22;
        xy = c * c * t12 + c * s * (t11 - t22) - s * s * t21;
        yx = c * c * t21 + c * s * (t11 - t22) - s * s * t12;
        yy = s * s * t11 + c * s * (t12 + t21) + c * c * t22;
      };
      diagnostics::DomainPoint q;
      q.X = {tip.tip.x + c * x1 - s * x2, tip.tip.y + s * x1 + c * x2};
      q.volume = dx * dx;
      double syx = 0.0;
      global(w.s11, w.s12, w.s12, w.s22, q.sxx, q.sxy, syx, q.syy);
      global(w.h11, w.h12, w.h21, w.h22, q.hxx, q.hxy, q.hyx, q.hyy);
      points.push_back(q);
      // The field is Hooke's (plane strain): its stress from its strain.
      if (std::hypot(x1, x2) > ring.r_in) {
        const double tr = w.h11 + w.h22;
        EXPECT_NEAR(w.s11, lambda * tr + 2 * mu * w.h11, 1e-6 * K_I / std::sqrt(ring.r_in));
        EXPECT_NEAR(w.s12, mu * (w.h12 + w.h21), 1e-6 * K_I / std::sqrt(ring.r_in));
      }
    }
  }
  const diagnostics::StressIntensity k =
      diagnostics::interaction_integral(points, tip, ring, E, nu);
  EXPECT_NEAR(k.K_I, K_I, 2e-3 * K_I);
  EXPECT_NEAR(k.K_II, K_II, 2e-3 * K_I);
  EXPECT_GT(k.points, 1000u);
}

// Erdogan & Sih's kink against its closed forms: none in pure mode I,
// acos(1/3) = 70.53 degrees in pure mode II, turning against K_II's sign;
// and, for mixed modes, the root of K_I sin + K_II (3 cos - 1) = 0 at which a
// scan of the near-tip hoop stress finds its greatest value.
TEST(CrackGrowth, MaximumTangentialStressKinkMatchesErdoganAndSih) {
  const double deg = 180.0 / std::numbers::pi;
  EXPECT_EQ(physics::max_tangential_stress_kink(1e7, 0.0), 0.0);
  const double mode_ii = std::acos(1.0 / 3.0) * deg;  // 70.5288 degrees
  EXPECT_NEAR(physics::max_tangential_stress_kink(0.0, 1e7) * deg, -mode_ii, 1e-9);
  EXPECT_NEAR(physics::max_tangential_stress_kink(0.0, -1e7) * deg, mode_ii, 1e-9);
  EXPECT_NEAR(mode_ii, 70.53, 0.005);
  for (const double ratio : {-3.0, -1.0, -0.3, 0.1, 0.5, 1.0, 4.0}) {
    const double K_I = 2e7, K_II = ratio * K_I;
    const double theta = physics::max_tangential_stress_kink(K_I, K_II);
    EXPECT_NEAR(K_I * std::sin(theta) + K_II * (3.0 * std::cos(theta) - 1.0), 0.0, 1e-8 * K_I);
    double best = -1e300, at = 0.0;
    for (int k = -18000; k <= 18000; ++k) {
      const double t = k * 1e-4;  // -1.8 to 1.8 rad: past +/- 70.53 degrees either way
      const double s = physics::near_tip_hoop_stress(K_I, K_II, t);
      if (s > best) best = s, at = t;
    }
    EXPECT_NEAR(theta, at, 2e-4) << "K_II / K_I = " << ratio;
    EXPECT_LT(theta * ratio, 0.0) << "turns against K_II";
  }
}

TEST(CrackGrowth, GrownTipTurnsTheAdvanceByTheKink) {
  const geometry::Point q = physics::grown_tip({1.0, 2.0}, {0.0, 1.0}, std::numbers::pi / 2, 0.5);
  EXPECT_NEAR(q.x, 0.5, 1e-15);  // advancing along +y, turned left: along -x
  EXPECT_NEAR(q.y, 2.0, 1e-15);
}

TEST(CrackedPlate, RefusesWhatItCannotModelAtTheField) {
  using testing_support::issues_of;
  auto plate = [](const nlohmann::json& crack) {
    return nlohmann::json{{"scene", {{"type", "cracked_plate"}, {"crack", crack}}}};
  };
  const auto long_edge = issues_of(plate({{"kind", "edge"}, {"length_m", 0.03}}));
  ASSERT_EQ(long_edge.size(), 1u);
  EXPECT_EQ(long_edge[0].pointer, "/scene/crack/length_m");
  EXPECT_NE(long_edge[0].message.find("0.6"), std::string::npos) << long_edge[0].message;
  const auto long_centre = issues_of(plate({{"kind", "centre"}, {"length_m", 0.035}}));
  ASSERT_EQ(long_centre.size(), 1u);
  EXPECT_EQ(long_centre[0].pointer, "/scene/crack/length_m");
  const auto kind = issues_of(plate({{"kind", "corner"}}));
  ASSERT_EQ(kind.size(), 1u);
  EXPECT_EQ(kind[0].pointer, "/scene/crack/kind");
  nlohmann::json coarse = plate({{"length_m", 0.004}});
  coarse["discretization"] = {{"spacing_m", 0.001}};
  const auto few = issues_of(coarse);
  ASSERT_EQ(few.size(), 1u);
  EXPECT_EQ(few[0].pointer, "/discretization");
  nlohmann::json ul = plate(nlohmann::json::object());
  ul["method"] = {{"formulation", "updated_lagrangian"}};
  const auto ul_issues = issues_of(ul);
  ASSERT_EQ(ul_issues.size(), 1u);
  EXPECT_EQ(ul_issues[0].pointer, "/method/formulation");
  nlohmann::json fitted = plate(nlohmann::json::object());
  fitted["discretization"] = {{"particles", "body_fitted"}};
  const auto fitted_issues = issues_of(fitted);
  ASSERT_EQ(fitted_issues.size(), 1u);
  EXPECT_EQ(fitted_issues[0].pointer, "/discretization/particles");
  // Growth: an increment shorter than 2 spacings or longer than the crack.
  for (const double increment : {0.0001, 0.02}) {
    nlohmann::json step = plate({{"length_m", 0.012}, {"increment_m", increment}});
    step["discretization"] = {{"spacing_m", 0.0006}};
    const auto step_issues = issues_of(step);
    ASSERT_EQ(step_issues.size(), 1u) << increment;
    EXPECT_EQ(step_issues[0].pointer, "/scene/crack/increment_m");
    EXPECT_NE(step_issues[0].message.find("at least 2 spacings"), std::string::npos);
  }
  const auto negative = issues_of(plate({{"max_increments", -1}}));
  ASSERT_EQ(negative.size(), 1u);
  EXPECT_EQ(negative[0].pointer, "/scene/crack/max_increments");
}

}  // namespace
}  // namespace gearsph
