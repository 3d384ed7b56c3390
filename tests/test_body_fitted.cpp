// Body-fitted particles (solver/geometry/body_fitted.hpp): on the outline,
// evenly spaced, graded as asked, with volumes that add up to the area, and
// the same particles every time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numbers>

#include "solver/geometry/body_fitted.hpp"
#include "solver/geometry/curve_sampling.hpp"
#include "solver/geometry/voronoi_cells.hpp"

namespace gearsph::geometry {
namespace {

constexpr double kPi = std::numbers::pi;

Polygon circle(double r, double cx = 0.0, double cy = 0.0, double tol = 1e-7) {
  Polygon out;
  sample_curve(
      [&](double a) {
        return Point{cx + r * std::cos(a), cy + r * std::sin(a)};
      },
      0.0, 2.0 * kPi, tol, out);
  return out;
}

Polygon rectangle(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

// Distance from each particle to its nearest neighbour, over the local spacing.
std::vector<double> nearest_over_spacing(const BodyFittedParticles& b) {
  std::vector<double> out;
  for (std::size_t i = 0; i < b.points.size(); ++i) {
    double best = 1e300;
    for (std::size_t j = 0; j < b.points.size(); ++j) {
      if (j != i) best = std::min(best, norm(b.points[i] - b.points[j]));
    }
    out.push_back(best / b.spacing[i]);
  }
  return out;
}

void dump(const std::string& name, const BodyFittedParticles& b) {
  if (!std::getenv("GEARSPH_DUMP")) return;
  std::ofstream f(name);
  for (std::size_t i = 0; i < b.points.size(); ++i) {
    f << b.points[i].x << ' ' << b.points[i].y << ' ' << b.volume[i] << ' ' << b.spacing[i] << ' '
      << int(b.outline[i]) << '\n';
  }
}

TEST(BodyFitted, RingVolumesAddUpToItsAreaAndTheOutlineRowsLieOnTheCircles) {
  const double a = 0.01, bo = 0.02, s = 1e-3;
  const Region ring = make_region(circle(bo), {circle(a)});
  const SpacingField field(s);
  const BodyFittedParticles p = fill_body_fitted(ring, field);
  dump("ring.txt", p);
  double total = 0.0;
  for (double v : p.volume) total += v;
  const double exact = kPi * (bo * bo - a * a);
  EXPECT_NEAR(total / exact, 1.0, 1e-4);  // the issue asks 0.1 %
  // The cells partition the ring; what is left is the snapping of the points
  // to Boost.Polygon's integer grid (2^-29 of the extent).
  EXPECT_NEAR(total / ring.area(), 1.0, 1e-8);
  // One particle per s^2 inside, and the outline rows' half cells: a
  // particle per s of outline for a band s/2 wide.
  const double perimeter = 2.0 * kPi * (a + bo);
  EXPECT_NEAR(double(p.points.size()) / (exact / (s * s) + 0.5 * perimeter / s), 1.0, 0.03);
  std::size_t on_outer = 0, on_inner = 0;
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    const double r = norm(p.points[i]);
    if (!p.outline[i]) {
      EXPECT_GT(r, a + 0.5 * s);
      EXPECT_LT(r, bo - 0.5 * s);
      continue;
    }
    // On the polygon, whose chords are within 0.1 um of the circles.
    EXPECT_TRUE(std::abs(r - a) < 1.1e-7 || std::abs(r - bo) < 1.1e-7) << r;
    (std::abs(r - bo) < 1.1e-7 ? on_outer : on_inner) += 1;
  }
  EXPECT_EQ(on_outer, static_cast<std::size_t>(std::lround(2 * kPi * bo / s)));
  EXPECT_EQ(on_inner, static_cast<std::size_t>(std::lround(2 * kPi * a / s)));
  const std::vector<double> nn = nearest_over_spacing(p);
  EXPECT_GT(*std::min_element(nn.begin(), nn.end()), 0.75);
  EXPECT_LT(*std::max_element(nn.begin(), nn.end()), 1.3);
  EXPECT_LT(p.last_move, 0.05);
}

// The spacing grows at the grading from the feature and rounds into the
// coarse spacing without a kink: a kink there left the relaxed particles a
// 2.5 % gap in their kernel sums where the grading ends.
TEST(BodyFitted, SpacingFieldGrowsAtTheGradingAndMeetsTheCoarseSpacingSmoothly) {
  SpacingField field(2e-3, 0.12);
  field.add_feature({{0.0, -1.0}, {0.0, 1.0}}, 0.25e-3);
  auto s = [&](double x) { return field({x, 0.0}); };
  EXPECT_NEAR(s(0.0), 0.25e-3, 1e-15);
  EXPECT_NEAR(s(2e-3), 0.25e-3 + 0.12 * 2e-3, 1e-15);  // well below the band
  double worst_slope_jump = 0.0, previous_slope = 0.0;
  const double step = 1e-5;
  for (double x = step; x < 30e-3; x += step) {
    EXPECT_LE(s(x), 2e-3 + 1e-15);
    EXPECT_GE(s(x), s(x - step));  // monotone away from the feature
    const double slope = (s(x) - s(x - step)) / step;
    if (x > step) worst_slope_jump = std::max(worst_slope_jump, std::abs(slope - previous_slope));
    previous_slope = slope;
  }
  EXPECT_NEAR(s(30e-3), 2e-3, 1e-15);
  // C1: the slope changes by a step's share of g / band, not by g at once.
  EXPECT_LT(worst_slope_jump, 0.01 * 0.12);
}

TEST(BodyFitted, GradedPlateFollowsItsSpacingFieldAndIsTheSameEveryTime) {
  // A plate with a hole, 0.25 mm at the hole, 2 mm far away (8:1).
  const Polygon hole = circle(2e-3);
  const Region plate = make_region(rectangle(-0.02, -0.01, 0.02, 0.01), {hole});
  SpacingField field(2e-3, 0.25);
  field.add_feature(hole, 0.25e-3, true);
  const BodyFittedParticles p = fill_body_fitted(plate, field);
  dump("plate.txt", p);
  double total = 0.0;
  for (double v : p.volume) {
    EXPECT_GT(v, 0.0);
    total += v;
  }
  EXPECT_NEAR(total / plate.area(), 1.0, 1e-6);  // clipping round-off
  const auto [lo, hi] = std::minmax_element(p.spacing.begin(), p.spacing.end());
  EXPECT_GE(*hi / *lo, 7.5);
  const std::vector<double> nn = nearest_over_spacing(p);
  EXPECT_GT(*std::min_element(nn.begin(), nn.end()), 0.6);
  EXPECT_LT(*std::max_element(nn.begin(), nn.end()), 1.4);
  // Corners of the rectangle carry a particle each.
  for (const Point c : rectangle(-0.02, -0.01, 0.02, 0.01)) {
    EXPECT_TRUE(std::any_of(p.points.begin(), p.points.end(),
                            [c](Point q) { return norm(q - c) < 1e-12; }));
  }
  const BodyFittedParticles again = fill_body_fitted(plate, field);
  ASSERT_EQ(again.points.size(), p.points.size());
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    EXPECT_EQ(again.points[i].x, p.points[i].x);
    EXPECT_EQ(again.points[i].y, p.points[i].y);
    EXPECT_EQ(again.volume[i], p.volume[i]);
  }
}

TEST(BodyFitted, AStraightEdgeFollowsASpacingGradedAlongIt) {
  // One long straight edge refined at one point in its middle (a rack flank
  // at a resolved contact): the outline row is fine there and coarse at the
  // ends, not the point's spacing all along the edge.
  const Polygon strip = rectangle(-0.01, -0.002, 0.01, 0.0);
  SpacingField field(1e-3, 0.12);
  field.add_feature({{0.0, 0.0}}, 0.05e-3);
  const BodyFittedParticles p = fill_body_fitted(make_region(strip), field);
  std::vector<double> top;
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    if (p.outline[i] && std::abs(p.points[i].y) < 1e-12) top.push_back(p.points[i].x);
  }
  std::sort(top.begin(), top.end());
  ASSERT_GT(top.size(), 10u);
  for (std::size_t k = 1; k < top.size(); ++k) {
    const double gap = top[k] - top[k - 1];
    const double expected = field({0.5 * (top[k] + top[k - 1]), 0.0});
    EXPECT_NEAR(gap / expected, 1.0, 0.15) << "between x = " << top[k - 1] << " and " << top[k];
  }
}

TEST(BodyFitted, VoronoiCellsOfALatticeAreItsSquares) {
  // Interior lattice points of a square: every cell dx^2, edge ones clipped.
  const double dx = 1e-3;
  const Region sq = make_region(rectangle(0, 0, 10 * dx, 10 * dx));
  std::vector<Point> pts;
  for (int a = 0; a < 10; ++a) {
    for (int b = 0; b < 10; ++b) pts.push_back({(a + 0.5) * dx, (b + 0.5) * dx});
  }
  const ClippedVoronoi v(sq, 3 * dx);
  // Four points on a circle meet at each Voronoi vertex, the degenerate case;
  // vertices come back within a few grid steps (2^-29 of the extent).
  for (const ClippedVoronoi::Cell& c : v.cells(pts)) EXPECT_NEAR(c.area / (dx * dx), 1.0, 2e-6);
}

}  // namespace
}  // namespace gearsph::geometry
