// Pinion and rack geometry (solver/geometry): sizes against the ISO 21771
// formulas, the outline against the exact involute, the undercut against an
// independent construction and a brute-force sweep of the cutter, the rack
// against the ISO 53 basic rack, the mesh placement, the lattice fill and the
// SVG picture.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "solver/geometry/gear_profile.hpp"
#include "solver/geometry/lattice_fill.hpp"
#include "solver/geometry/mesh_placement.hpp"
#include "solver/geometry/polygon.hpp"
#include "solver/geometry/rack_profile.hpp"
#include "solver/geometry/svg.hpp"

namespace gearsph::geometry {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
constexpr double kMicron = 1e-6;

PinionSpec pinion_spec(int z, double m, double alpha_deg, double x, double backlash = 0.0) {
  PinionSpec s;
  s.teeth = z;
  s.tool.module_m = m;
  s.tool.pressure_angle_rad = alpha_deg * kDeg;
  s.profile_shift = x;
  s.backlash_m = backlash;
  return s;
}

double involute_fn(double a) {
  return std::tan(a) - a;
}

// Angle of p relative to `centre`, wrapped to (-pi, pi].
double relative_angle(Point p, double centre) {
  return std::remainder(std::atan2(p.y, p.x) - centre, 2.0 * kPi);
}

// Points where the ring crosses the circle of radius R.
std::vector<Point> circle_crossings(const Polygon& ring, double R) {
  std::vector<Point> out;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
    const Point a = ring[i], d = ring[(i + 1) % n] - a;
    const double qa = dot(d, d), qb = 2.0 * dot(a, d), qc = dot(a, a) - R * R;
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc < 0.0) continue;
    for (const double sign : {-1.0, 1.0}) {
      const double t = (-qb + sign * std::sqrt(disc)) / (2.0 * qa);
      if (t >= 0.0 && t < 1.0) out.push_back(a + t * d);
    }
  }
  return out;
}

// Arc thickness at radius R of the tooth centred at `centre`: the nearest
// crossing on either side of the tooth axis.
double arc_thickness(const Polygon& ring, double R, double centre) {
  double left = kPi, right = -kPi;
  for (const Point& p : circle_crossings(ring, R)) {
    const double a = relative_angle(p, centre);
    if (a > 0.0) left = std::min(left, a);
    if (a < 0.0) right = std::max(right, a);
  }
  return R * (left - right);
}

// ---------------------------------------------------------------------------
// Sizes

struct Case {
  int z;
  double m, alpha_deg, x;
};
const Case kCases[] = {{12, 4e-3, 20.0, 0.0},  {12, 4e-3, 20.0, 0.3}, {20, 2e-3, 20.0, -0.2},
                       {30, 1e-3, 22.5, 0.5},  {8, 4e-3, 20.0, 0.0},  {17, 3e-3, 14.5, 0.1},
                       {40, 5e-3, 20.0, -0.4}, {10, 6e-3, 22.5, 0.25}};

// Arc length along a polyline, as the fillets and the FE model walk their
// outlines: an L of legs 3 and 4 (a repeated vertex adds no length).
TEST(GearGeometry, PointsAtArcLengthAlongAPolyline) {
  const std::vector<Point> line = {{0, 0}, {3, 0}, {3, 0}, {3, 4}};
  const std::vector<double> cum = cumulative_arc(line);
  ASSERT_EQ(cum.size(), line.size());
  EXPECT_DOUBLE_EQ(cum[1], 3.0);
  EXPECT_DOUBLE_EQ(cum[2], 3.0);
  EXPECT_DOUBLE_EQ(cum[3], 7.0);
  const Point mid = at_arc(line, cum, 1.5);
  EXPECT_DOUBLE_EQ(mid.x, 1.5);
  EXPECT_DOUBLE_EQ(mid.y, 0.0);
  const Point up = at_arc(line, cum, 5.0);  // 2 up the second leg
  EXPECT_DOUBLE_EQ(up.x, 3.0);
  EXPECT_DOUBLE_EQ(up.y, 2.0);
  // Beyond either end: the end.
  EXPECT_DOUBLE_EQ(at_arc(line, cum, -1.0).x, 0.0);
  EXPECT_DOUBLE_EQ(at_arc(line, cum, 9.0).y, 4.0);
}

TEST(GearGeometry, RadiiFollowTheFormulasAndTheOutline) {
  for (const Case& c : kCases) {
    SCOPED_TRACE("z=" + std::to_string(c.z) + " x=" + std::to_string(c.x));
    const PinionGeometry g(pinion_spec(c.z, c.m, c.alpha_deg, c.x));
    const double r = c.m * c.z / 2.0, a = c.alpha_deg * kDeg;
    EXPECT_DOUBLE_EQ(g.pitch_radius(), r);
    EXPECT_DOUBLE_EQ(g.base_radius(), r * std::cos(a));
    EXPECT_NEAR(g.tip_radius(), r + c.m * (1.0 + c.x), 1e-15);
    EXPECT_NEAR(g.root_radius(), r - c.m * (1.25 - c.x), 1e-15);
    double r_min = 1e9, r_max = 0.0;
    for (const Point& p : g.outline()) {
      r_min = std::min(r_min, norm(p));
      r_max = std::max(r_max, norm(p));
    }
    EXPECT_NEAR(r_max, g.tip_radius(), 1e-12);
    EXPECT_NEAR(r_min, g.root_radius(), 1e-12);
  }
  // The seed paper's pinion: z = 12, m = 4 mm, alpha = 20 deg, x = 0.
  const PinionGeometry paper(pinion_spec(12, 4e-3, 20.0, 0.0));
  EXPECT_NEAR(paper.pitch_radius(), 24e-3, 1e-15);
  EXPECT_NEAR(paper.tip_radius(), 28e-3, 1e-15);
  EXPECT_NEAR(paper.root_radius(), 19e-3, 1e-15);
  EXPECT_NEAR(paper.base_radius(), 22.5526e-3, 1e-7);
}

TEST(GearGeometry, ToothThicknessAtThePitchCircleFromTheOutline) {
  for (const Case& c : kCases) {
    for (const double backlash : {0.0, 0.1e-3}) {
      SCOPED_TRACE("z=" + std::to_string(c.z) + " x=" + std::to_string(c.x) +
                   " j=" + std::to_string(backlash));
      const PinionGeometry g(pinion_spec(c.z, c.m, c.alpha_deg, c.x, backlash));
      const double expected =
          c.m * (kPi / 2.0 + 2.0 * c.x * std::tan(c.alpha_deg * kDeg)) - backlash;
      EXPECT_NEAR(g.pitch_thickness(), expected, 1e-15);
      const Polygon ring = g.outline();
      for (int k = 0; k < c.z; ++k) {
        EXPECT_NEAR(arc_thickness(ring, g.pitch_radius(), g.tooth_centre_angle(k)), expected,
                    1.0 * kMicron);
      }
    }
  }
}

TEST(GearGeometry, ToothZeroPointsDownAndTeethAreNumberedCounterClockwise) {
  const PinionGeometry g(pinion_spec(12, 4e-3, 20.0, 0.0));
  EXPECT_DOUBLE_EQ(g.tooth_centre_angle(0), -kPi / 2.0);
  EXPECT_NEAR(g.tooth_centre_angle(3), 0.0, 1e-15);
  const Polygon ring = g.outline();
  const auto lowest =
      *std::min_element(ring.begin(), ring.end(), [](Point a, Point b) { return a.y < b.y; });
  EXPECT_NEAR(lowest.y, -g.tip_radius(), 1e-12);
  // The tooth on the -y axis is symmetric about it.
  const auto at_pitch = circle_crossings(ring, g.pitch_radius());
  int below = 0;
  for (const Point& p : at_pitch) {
    if (p.y < 0.0 && std::abs(p.x) < 5e-3) {
      ++below;
      EXPECT_NEAR(std::abs(p.x),
                  g.pitch_radius() * std::sin(g.pitch_thickness() / 2.0 / g.pitch_radius()), 1e-7);
    }
  }
  EXPECT_EQ(below, 2);
}

// ---------------------------------------------------------------------------
// Flank and fillet

TEST(GearGeometry, FlankAboveTheFormCircleIsTheInvoluteOfTheBaseCircle) {
  for (const Case& c : kCases) {
    SCOPED_TRACE("z=" + std::to_string(c.z) + " x=" + std::to_string(c.x));
    const PinionGeometry g(pinion_spec(c.z, c.m, c.alpha_deg, c.x));
    const double rb = g.base_radius();
    // Exact involute half angle, ISO 21771:2007 tooth thickness on a circle:
    // s_y / (2 r_y) = s / (2 r) + inv(alpha) - inv(alpha_y).
    auto involute_psi = [&](double ry) {
      return g.pitch_thickness() / (2.0 * g.pitch_radius()) + involute_fn(c.alpha_deg * kDeg) -
             involute_fn(std::acos(rb / ry));
    };
    auto error = [&](Point p) {  // along the circle: an upper bound of the distance
      const double ry = norm(p);
      return ry * std::abs(std::abs(std::atan2(p.x, p.y)) - involute_psi(ry));
    };
    const std::vector<Point>& half = g.half_tooth();
    int checked = 0;
    double worst = 0.0;
    for (std::size_t i = 0; i + 1 < half.size(); ++i) {
      const double r0 = norm(half[i]), r1 = norm(half[i + 1]);
      const bool on_flank = r0 >= g.form_radius() && r1 < g.tip_radius() - 1e-12;
      if (!on_flank) continue;
      worst = std::max({worst, error(half[i]), error(0.5 * (half[i] + half[i + 1]))});
      ++checked;
    }
    EXPECT_GT(checked, 20);
    EXPECT_LT(worst, 0.2 * kMicron);  // vertices exact, chords within the 0.1 um tolerance
    // The same holds on the assembled outline, every tooth, both flanks.
    const Polygon ring = g.outline();
    for (const Point& p : ring) {
      const double ry = norm(p);
      if (ry <= g.form_radius() + 1e-9 || ry >= g.tip_radius() - 1e-9) continue;
      const double k = std::round((std::atan2(p.y, p.x) + kPi / 2.0) / g.angular_pitch());
      const double psi = std::abs(relative_angle(p, g.tooth_centre_angle(static_cast<int>(k))));
      ASSERT_LT(ry * std::abs(psi - involute_psi(ry)), 1.0 * kMicron);
    }
  }
}

TEST(GearGeometry, UndercutAppearsBelowTheClassicalLimit) {
  const double a = 20.0 * kDeg;
  // Straight-flank depth of the ISO 53 tool, h_fP - rho_fP (1 - sin a) = 0.99996.
  const double h_fl = 1.25 - 0.38 * (1.0 - std::sin(a));
  const double x_min = h_fl - 12.0 * std::sin(a) * std::sin(a) / 2.0;  // 0.298 for z = 12
  EXPECT_NEAR(x_min, 0.298, 5e-4);
  EXPECT_TRUE(PinionGeometry(pinion_spec(12, 4e-3, 20.0, 0.0)).undercut());
  EXPECT_FALSE(PinionGeometry(pinion_spec(12, 4e-3, 20.0, 0.3)).undercut());
  EXPECT_TRUE(PinionGeometry(pinion_spec(12, 4e-3, 20.0, x_min - 1e-4)).undercut());
  EXPECT_FALSE(PinionGeometry(pinion_spec(12, 4e-3, 20.0, x_min + 1e-4)).undercut());
  // z_min = 2 h_fl / sin^2(alpha) = 17.1 with x = 0.
  EXPECT_TRUE(PinionGeometry(pinion_spec(17, 4e-3, 20.0, 0.0)).undercut());
  EXPECT_FALSE(PinionGeometry(pinion_spec(18, 4e-3, 20.0, 0.0)).undercut());
}

// Independent construction of the undercut point (Litvin & Fuentes, Gear
// Geometry and Applied Theory, 2004, ch. 6 and 11): in the gear frame the tip
// round's centre traces an extended involute (trochoid) as the tool's rolling
// line rolls on the pitch circle; the fillet is the curve parallel to it at
// the distance rho_fP. The undercut point is where this parallel curve, walked
// up from the root, first reaches the involute (ISO 21771 half angle).
double undercut_radius_by_trochoid(int z, double m, double alpha, double x) {
  const double r = m * z / 2.0, rb = r * std::cos(alpha), rho = 0.38 * m;
  const double b = 1.25 * m - rho - x * m;  // round centre depth below the rolling line
  // Its offset along the rolling line from the tooth axis: the tool flank
  // passes the rolling line at half the tooth thickness and widens by tan(a).
  const double u =
      m * (kPi / 4.0 + x * std::tan(alpha)) + b * std::tan(alpha) + rho / std::cos(alpha);
  auto fillet = [&](double phi) {  // rolled by phi: contact point at half angle phi
    const Point t{std::cos(phi), -std::sin(phi)}, n{-std::sin(phi), -std::cos(phi)};
    const Point c = r * Point{std::sin(phi), std::cos(phi)} + (u - r * phi) * t + b * n;
    const Point dc = (u - r * phi) * n - b * t;  // d c / d phi
    const Point normal = (1.0 / norm(dc)) * Point{-dc.y, dc.x};
    return c + rho * normal;
  };
  const double s_half = m * (kPi / 2.0 + 2.0 * x * std::tan(alpha)) / (2.0 * r);
  auto gap = [&](double phi) {  // > 0: outside the involute tooth
    const Point p = fillet(phi);
    const double ry = norm(p);
    return std::atan2(p.x, p.y) - (s_half + involute_fn(alpha) - involute_fn(std::acos(rb / ry)));
  };
  // Walk from the root (phi = u / r) up the right flank (growing phi).
  const double phi0 = u / r, step = 1e-5;
  auto outside = [&](double phi) { return norm(fillet(phi)) >= rb && gap(phi) >= 0.0; };
  double prev = phi0;
  while (!outside(prev + step)) {
    prev += step;
    if (prev > phi0 + kPi / 2.0) return std::nan("");  // never reached the involute
  }
  double next = prev + step;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (prev + next);
    (outside(mid) ? next : prev) = mid;
  }
  return norm(fillet(next));
}

TEST(GearGeometry, UndercutStartMatchesTheTrochoidConstruction) {
  for (const Case& c : {Case{12, 4e-3, 20.0, 0.0}, Case{8, 4e-3, 20.0, 0.0},
                        Case{10, 2e-3, 20.0, 0.1}, Case{12, 4e-3, 20.0, 0.2}}) {
    SCOPED_TRACE("z=" + std::to_string(c.z) + " x=" + std::to_string(c.x));
    const PinionGeometry g(pinion_spec(c.z, c.m, c.alpha_deg, c.x));
    ASSERT_TRUE(g.undercut());
    const double expected = undercut_radius_by_trochoid(c.z, c.m, c.alpha_deg * kDeg, c.x);
    EXPECT_NEAR(g.form_radius(), expected, 1e-9);
    EXPECT_GT(g.form_radius(), g.base_radius());
  }
  // The seed paper's pinion: the involute is cut back to 22.605 mm (r_b = 22.553 mm).
  const PinionGeometry paper(pinion_spec(12, 4e-3, 20.0, 0.0));
  EXPECT_NEAR(paper.form_radius(), 22.6054e-3, 1e-7);
}

TEST(GearGeometry, FormRadiusWithoutUndercutMatchesTheIsoClosedForm) {
  for (const Case& c : {Case{12, 4e-3, 20.0, 0.3}, Case{20, 2e-3, 20.0, 0.0},
                        Case{30, 1e-3, 22.5, -0.2}, Case{40, 5e-3, 20.0, 0.5}}) {
    SCOPED_TRACE("z=" + std::to_string(c.z) + " x=" + std::to_string(c.x));
    const PinionGeometry g(pinion_spec(c.z, c.m, c.alpha_deg, c.x));
    ASSERT_FALSE(g.undercut());
    // ISO 21771:2007 generated root form diameter of a rack-type tool:
    // d_Ff = sqrt(d_b^2 + (d sin a - 2 (h_fP - x m - rho_fP (1 - sin a)) / sin a)^2).
    const double a = c.alpha_deg * kDeg, d = c.m * c.z;
    const double h = 1.25 * c.m - c.x * c.m - 0.38 * c.m * (1.0 - std::sin(a));
    const double d_ff = std::hypot(d * std::cos(a), d * std::sin(a) - 2.0 * h / std::sin(a));
    EXPECT_NEAR(g.form_radius(), d_ff / 2.0, 1e-12);
  }
}

// Brute force, no envelope theory: a gear point is cut when, for some tool
// displacement, it lies within rho_fP of the tool tooth shrunk by rho_fP (the
// wedge behind the tool's left flank and tip line). The tooth boundary at a
// radius is the smallest half angle that gets cut.
double swept_boundary_half_angle(int z, double m, double alpha, double x, double R) {
  const double r = m * z / 2.0, rho = 0.38 * m;
  const double yc = r + x * m - 1.25 * m + rho;  // round centre height
  const double xc = m * kPi / 4.0 + (1.25 * m - rho) * std::tan(alpha) + rho / std::cos(alpha);
  const Point along{-std::sin(alpha), std::cos(alpha)}, into{std::cos(alpha), std::sin(alpha)};
  auto wedge_distance = [&](Point p) {
    const Point q = p - Point{xc, yc};
    if (q.y >= 0.0 && dot(q, into) >= 0.0) return 0.0;
    const double d_tip = norm(q - Point{std::max(q.x, 0.0), 0.0});
    const double d_flank = norm(q - std::max(dot(q, along), 0.0) * along);
    return std::min(d_tip, d_flank);
  };
  auto distance_at = [&](Point g, double s) {  // tool moved by s, gear turned by s / r
    return wedge_distance(rotate(g, -s / r) - Point{s, 0.0});
  };
  auto is_cut = [&](double psi) {
    const Point g{R * std::sin(psi), R * std::cos(psi)};
    double best = 1e9, s_best = 0.0;
    const int steps = 3000;
    for (int i = 0; i <= steps; ++i) {
      const double s = m * (-8.0 + 12.0 * i / steps);
      const double d = distance_at(g, s);
      if (d < best) {
        best = d;
        s_best = s;
      }
    }
    for (double h = 12.0 * m / steps; h > 1e-13; h *= 0.6) {
      for (const double s : {s_best - h, s_best + h}) {
        const double d = distance_at(g, s);
        if (d < best) {
          best = d;
          s_best = s;
        }
      }
    }
    return best <= rho;
  };
  double lo = 0.0, hi = kPi / z;
  for (int i = 0; i < 50; ++i) (is_cut(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
  return lo;
}

// Half angle where the half tooth first reaches radius R.
double outline_half_angle(const std::vector<Point>& half, double R) {
  for (std::size_t i = 0; i + 1 < half.size(); ++i) {
    const double r0 = norm(half[i]), r1 = norm(half[i + 1]);
    if (r0 < R && r1 >= R) {
      const Point p = half[i] + ((R - r0) / (r1 - r0)) * (half[i + 1] - half[i]);
      return std::atan2(p.x, p.y);
    }
  }
  return -1.0;
}

TEST(GearGeometry, OutlineMatchesABruteForceSweepOfTheCutter) {
  for (const Case& c : {Case{12, 4e-3, 20.0, 0.0}, Case{8, 4e-3, 20.0, 0.0}}) {
    SCOPED_TRACE("z=" + std::to_string(c.z));
    const PinionGeometry g(pinion_spec(c.z, c.m, c.alpha_deg, c.x));
    const double rb = g.base_radius();
    // Fillet, undercut below and above the base circle, involute.
    for (const double R :
         {g.root_radius() + 0.3e-3, rb - 0.5e-3, rb - 0.02e-3, 0.5 * (rb + g.form_radius()),
          g.form_radius() + 0.02e-3, g.pitch_radius(), g.tip_radius() - 0.3e-3}) {
      const double brute = swept_boundary_half_angle(c.z, c.m, c.alpha_deg * kDeg, c.x, R);
      EXPECT_NEAR(R * outline_half_angle(g.half_tooth(), R), R * brute, 0.25 * kMicron) << R;
    }
  }
}

// ---------------------------------------------------------------------------
// Outline validity, sectors

void expect_valid_ring(const Polygon& ring) {
  ASSERT_GE(ring.size(), 3u);
  EXPECT_GT(signed_area(ring), 0.0) << "not counter-clockwise";
  EXPECT_GT(shortest_edge(ring), 1e-10) << "repeated vertex (first == last counts too)";
  const auto hit = find_self_intersection(ring);
  EXPECT_FALSE(hit.has_value()) << "edges " << hit->first << " and " << hit->second << " meet";
}

TEST(GearGeometry, OutlinesAreClosedCounterClockwiseAndSimple) {
  for (const Case& c : kCases) {
    SCOPED_TRACE("z=" + std::to_string(c.z) + " x=" + std::to_string(c.x));
    const PinionGeometry g(pinion_spec(c.z, c.m, c.alpha_deg, c.x));
    expect_valid_ring(g.outline());
    expect_valid_ring(g.sector_outline(-1, 1, 0.5 * g.root_radius()));
    expect_valid_ring(g.sector_outline(0, 0, 0.0));
  }
  // Close to the undercut limit, where the fillet meets the involute's foot.
  for (const double x : {0.2975, 0.298, 0.2981, 0.2982}) {
    expect_valid_ring(PinionGeometry(pinion_spec(12, 4e-3, 20.0, x)).outline());
  }
  RackSpec rack;
  expect_valid_ring(RackGeometry(rack).outline());
  rack.tip_radius_coef = 0.2;
  rack.backlash_m = 0.1e-3;
  expect_valid_ring(RackGeometry(rack).outline());
}

TEST(GearGeometry, SectorIsItsShareOfTheGearMinusTheBore) {
  const PinionGeometry g(pinion_spec(12, 4e-3, 20.0, 0.0));
  const double full = signed_area(g.outline());
  const double ri = 10e-3;
  const Polygon sector = g.sector_outline(-1, 1, ri);
  // The bore arc is polygonised: allow its chord error over its length.
  const double expected = 3.0 / 12.0 * (full - kPi * ri * ri);
  EXPECT_NEAR(signed_area(sector), expected, 1e-7 * perimeter(sector));
  double pies = 0.0;
  for (int k = 0; k < 12; ++k) pies += signed_area(g.sector_outline(k, k, 0.0));
  EXPECT_NEAR(pies, full, 1e-12 * full);
  EXPECT_THROW(g.sector_outline(0, 11, ri), std::invalid_argument);
  EXPECT_THROW(g.sector_outline(0, 2, g.root_radius()), std::invalid_argument);
  EXPECT_EQ(g.sector_outline(0, 11, 0.0).size(), g.outline().size());
}

TEST(GearGeometry, InvalidPinionsAreRejected) {
  EXPECT_THROW(PinionGeometry(pinion_spec(2, 4e-3, 20.0, 0.0)), std::invalid_argument);
  EXPECT_THROW(PinionGeometry(pinion_spec(12, 4e-3, 20.0, 1.0)), std::invalid_argument);  // pointed
  EXPECT_THROW(PinionGeometry(pinion_spec(12, -1.0, 20.0, 0.0)), std::invalid_argument);
  PinionSpec fat = pinion_spec(12, 4e-3, 20.0, 0.0);
  fat.tool.root_radius_coef = 0.5;  // > 0.472 m fits the ISO 53 space
  EXPECT_THROW(PinionGeometry{fat}, std::invalid_argument);
}

// ---------------------------------------------------------------------------
// Rack

TEST(GearGeometry, RackHasTheBasicRackProfile) {
  for (const double backlash : {0.0, 0.1e-3}) {
    RackSpec spec;
    spec.teeth = 4;
    spec.backlash_m = backlash;
    const RackGeometry rack(spec);
    const double m = spec.profile.module_m, p = kPi * m, a = spec.profile.pressure_angle_rad;
    EXPECT_DOUBLE_EQ(rack.pitch(), p);
    const Polygon& ring = rack.outline();
    const Box box = bounding_box(ring);
    EXPECT_DOUBLE_EQ(box.hi.y, 1.0 * m);
    EXPECT_DOUBLE_EQ(box.lo.y, -1.25 * m - spec.back_thickness_m);
    EXPECT_NEAR(box.hi.x - box.lo.x, 4 * p, 1e-15);
    // Datum line crossings: the body sides, then both flanks of every tooth.
    std::vector<double> xs;
    double xc = 0.0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      if (edge_crossing(ring[i], ring[(i + 1) % ring.size()], 0.0, xc)) xs.push_back(xc);
    }
    std::sort(xs.begin(), xs.end());
    ASSERT_EQ(xs.size(), 8u);
    for (int j = 0; j < 4; ++j) {
      EXPECT_NEAR(xs[2 * j + 1] - xs[2 * j], p / 2.0 - backlash, 1e-15);  // thickness at datum
      EXPECT_NEAR(0.5 * (xs[2 * j] + xs[2 * j + 1]), rack.tooth_centre_x(j), 1e-15);
      if (j > 0) {
        EXPECT_NEAR(xs[2 * j] - xs[2 * j - 2], p, 1e-15);  // pitch
      }
    }
    // Area: body, trapezoidal teeth, and the root fillets' corner fill
    // rho^2 (cot(g/2) - (pi - g)/2) for the corner angle g = 90 deg + alpha.
    const double ha = m, hf = 1.25 * m, rho = 0.38 * m, t = p / 2.0 - backlash;
    const double g_corner = kPi / 2.0 + a;
    const double fill = rho * rho * (1.0 / std::tan(g_corner / 2.0) - (kPi - g_corner) / 2.0);
    const double area =
        4 * p * spec.back_thickness_m + 4 * (ha + hf) * (t - (ha - hf) * std::tan(a)) + 8 * fill;
    EXPECT_NEAR(signed_area(ring), area, 1e-7 * perimeter(ring));
  }
}

// ---------------------------------------------------------------------------
// Mesh

// Largest depth of vertices of `a` inside `b` and smallest gap between them,
// looking only at vertices within `zone` of the rolling line.
std::pair<double, double> penetration_and_gap(const Polygon& a, const Polygon& b, double rolling_y,
                                              double zone) {
  double depth = 0.0, gap = 1e9;
  for (const Point& v : a) {
    if (std::abs(v.y - rolling_y) > zone) continue;
    const double d = distance_to_polyline(b, v, true);
    if (is_inside(b, v))
      depth = std::max(depth, d);
    else
      gap = std::min(gap, d);
  }
  return {depth, gap};
}

TEST(GearGeometry, PlacedPinionAndRackMeshWithoutInterference) {
  for (const double backlash : {0.0, 0.08e-3}) {
    SCOPED_TRACE("backlash per part " + std::to_string(backlash));
    const PinionGeometry pinion(pinion_spec(12, 4e-3, 20.0, 0.0, backlash));
    RackSpec rack_spec;
    rack_spec.backlash_m = backlash;
    const RackGeometry rack(rack_spec);
    const Point centre{0.01, 0.05};
    const Polygon teeth = pinion.sector_outline(-2, 2, 12e-3);
    const double r = pinion.pitch_radius(), p = rack.pitch();
    // Both parts thinned by j: play 2 j along the pitch line, j on each side,
    // j cos(alpha) normal to the flanks.
    const double normal_gap = backlash * std::cos(20.0 * kDeg);
    for (const double travel : {-0.5 * p, -0.2 * p, 0.0, 0.13 * p, 0.37 * p}) {
      const MeshPlacement mp = place_in_mesh(pinion, rack, centre, 0, 2, travel);
      EXPECT_NEAR(mp.centre_distance, r, 1e-15);
      EXPECT_NEAR(mp.rolling_line_y, centre.y - r, 1e-15);
      EXPECT_NEAR(mp.rack.shift.y, centre.y - r, 1e-15);  // x = 0: datum on the rolling line
      // Tooth 0 turned by travel / r counter-clockwise from straight down.
      const Point tip = mp.pinion.apply(Point{0.0, -pinion.tip_radius()});
      EXPECT_NEAR(std::atan2(tip.y - centre.y, tip.x - centre.x), -kPi / 2.0 + travel / r, 1e-12);
      const Polygon pw = transformed(teeth, mp.pinion), rw = transformed(rack.outline(), mp.rack);
      const double zone = 1.3 * 4e-3;
      const auto [depth_p, gap_p] = penetration_and_gap(pw, rw, mp.rolling_line_y, zone);
      const auto [depth_r, gap_r] = penetration_and_gap(rw, pw, mp.rolling_line_y, zone);
      EXPECT_LT(std::max(depth_p, depth_r), 0.3 * kMicron) << "travel " << travel;
      // Flank to flank the gap is exactly normal_gap (an involute turned by
      // delta moves r_b delta along its normal); the rack's sharp tip corner
      // sweeping the pinion's undercut comes up to 0.4 um closer.
      EXPECT_NEAR(std::min(gap_p, gap_r), normal_gap, 1.0 * kMicron) << "travel " << travel;
    }
  }
}

TEST(GearGeometry, ShiftedPinionSitsAtCentreDistanceRPlusXm) {
  const PinionGeometry pinion(pinion_spec(12, 4e-3, 20.0, 0.3));
  const RackGeometry rack{RackSpec{}};
  const MeshPlacement mp = place_in_mesh(pinion, rack, {0.0, 0.0}, 1, 3, 0.0);
  EXPECT_NEAR(mp.centre_distance, 24e-3 + 1.2e-3, 1e-15);
  EXPECT_NEAR(mp.rack.shift.y, -25.2e-3, 1e-15);
  EXPECT_NEAR(mp.rolling_line_y, -24e-3, 1e-15);
  EXPECT_NEAR(mp.rack.apply({rack.space_centre_x(3), 0.0}).x, 0.0, 1e-15);
  const Polygon pw = transformed(pinion.sector_outline(0, 2, 12e-3), mp.pinion);
  const Polygon rw = transformed(rack.outline(), mp.rack);
  const auto [depth, gap] = penetration_and_gap(pw, rw, mp.rolling_line_y, 6e-3);
  EXPECT_LT(depth, 0.3 * kMicron);
  EXPECT_LT(gap, 0.5 * kMicron);  // tight mesh
}

// The modelled rack keeps its straight flank 0.05 m below where the
// pinion's tip reaches (a standard tip: 1.0 m below the datum line at any
// shift). ISO 53 A at 20 degrees ends it at 0.99996 m, inside the tip's
// reach, so its root fillet shrinks to (1.25 - 1.05) / (1 - sin 20 deg) =
// 0.304 m; at 16 degrees to 0.276 m; at 25 degrees the default tool's 0.29 m
// already clears (its flank ends at 1.083 m) and is kept.
TEST(GearGeometry, TheModelledRackKeepsItsFlankBelowThePinionsTip) {
  for (const double x : {-0.35, 0.0, 0.5}) {
    const PinionGeometry pinion(pinion_spec(25, 3.5e-3, 20.0, x));
    EXPECT_NEAR(tip_reach_below_datum(pinion), 3.5e-3, 1e-12) << x;
    const BasicRack rack = mating_rack_shape(pinion, 1).profile;
    EXPECT_NEAR(rack.root_radius_coef, 0.2 / (1.0 - std::sin(20.0 * std::numbers::pi / 180.0)),
                1e-9)
        << x;
    EXPECT_NEAR(rack.straight_flank_depth(), 1.05 * 3.5e-3, 1e-12) << x;
  }
  const PinionGeometry low(pinion_spec(57, 3.25e-3, 16.0, -0.25));
  EXPECT_NEAR(mating_rack_shape(low, 1).profile.root_radius_coef,
              0.2 / (1.0 - std::sin(16.0 * std::numbers::pi / 180.0)), 1e-9);
  PinionSpec wide = pinion_spec(25, 3.5e-3, 25.0, 0.0);
  wide.tool.root_radius_coef = wide.tool.default_root_radius_coef(0.0);
  const PinionGeometry steep(wide);
  EXPECT_EQ(mating_rack_shape(steep, 1).profile.root_radius_coef, wide.tool.root_radius_coef);
}

// The modelled rack's tip is rounded so that its straight flank ends 0.05 m
// below the pinion's form circle, which the cutter's flank end generated at
// h_fP - rho_fP (1 - sin alpha) above the datum line: ISO 53 A at 20 degrees
// puts it at 0.99996 m, inside the rack's 1.0 m addendum, so the round is
// (1.0 - 0.99996 + 0.05) / (1 - sin 20 deg) = 0.0761 m; at 16 degrees the form
// is lower (0.9747 m) and the round larger, 0.1039 m; a 25 degree tool's
// 0.29 m fillet ends its flank at 1.083 m and the tip stays sharp. On the
// built outline the flank is straight up to that height and falls away from
// the flank line above it. A rack of one tooth (a static check's) keeps the
// sharp tip: its driving flank bears on tooth 0 and its reverse flank
// touches nothing, so its tip meets no fillet.
TEST(GearGeometry, TheModelledRackRoundsItsTipClearOfThePinionsFillet) {
  const double m = 3.5e-3;
  auto round = [&](double alpha_deg, double rho_fP) {
    PinionSpec spec = pinion_spec(25, m, alpha_deg, 0.0);
    spec.tool.root_radius_coef = rho_fP;
    return mating_rack_shape(PinionGeometry(spec), 3).tip_radius_coef;
  };
  const auto tip_round = [](double alpha_deg, double rho_fP) {
    const double s = std::sin(alpha_deg * std::numbers::pi / 180.0);
    const double form = 1.25 - rho_fP * (1.0 - s);
    return (1.0 - form + 0.05) / (1.0 - s);
  };
  EXPECT_NEAR(round(20.0, 0.38), tip_round(20.0, 0.38), 1e-9);
  EXPECT_NEAR(round(20.0, 0.38), 0.0761, 1e-4);
  EXPECT_NEAR(round(16.0, 0.38), 0.1039, 1e-4);
  EXPECT_EQ(round(25.0, 0.29), 0.0);
  // A rack of one tooth keeps the sharp tip: its tip meets no fillet.
  EXPECT_EQ(mating_rack_shape(PinionGeometry(pinion_spec(25, m, 20.0, 0.0)), 1).tip_radius_coef,
            0.0);

  for (const double x : {-0.3, 0.0, 0.4}) {
    const PinionGeometry pinion(pinion_spec(25, m, 20.0, x));
    const MatingRackShape shape = mating_rack_shape(pinion, 3);
    RackSpec rs;
    rs.profile = shape.profile;
    rs.tip_radius_coef = shape.tip_radius_coef;
    const RackGeometry rack(rs);
    const double a = rs.profile.pressure_angle_rad;
    const double flank_top = pinion.spec().tool.straight_flank_depth() - 0.05 * m;
    int above = 0;
    for (const Point& q : rack.half_tooth()) {
      const double on_line = rack.datum_thickness() / 2.0 - q.y * std::tan(a);
      if (q.y < -rs.profile.straight_flank_depth()) continue;  // the root fillet
      if (q.y <= flank_top + 1e-12) {
        EXPECT_NEAR(q.x, on_line, 1e-9) << "x " << x << ", y " << q.y;
      } else if (q.y < rack.tip_y() - 1e-12) {
        EXPECT_LT(q.x, on_line - 1e-12) << "x " << x << ", y " << q.y;
        ++above;
      }
    }
    EXPECT_GT(above, 3) << x;  // the round is sampled
  }
}

// ---------------------------------------------------------------------------
// Polygon helpers and lattice fill

TEST(GearGeometry, InsideTestFollowsTheDocumentedBoundaryRule) {
  const Polygon square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_DOUBLE_EQ(signed_area(square), 1.0);
  EXPECT_DOUBLE_EQ(perimeter(square), 4.0);
  EXPECT_TRUE(is_inside(square, {0.5, 0.5}));
  EXPECT_TRUE(is_inside(square, {0.0, 0.5}));   // left edge: polygon on its +x side
  EXPECT_FALSE(is_inside(square, {1.0, 0.5}));  // right edge
  EXPECT_TRUE(is_inside(square, {0.5, 0.0}));   // bottom edge: polygon above
  EXPECT_FALSE(is_inside(square, {0.5, 1.0}));  // top edge
  EXPECT_TRUE(is_inside(square, {0.0, 0.0}));   // lower left corner only
  EXPECT_FALSE(is_inside(square, {1.0, 0.0}));
  EXPECT_FALSE(is_inside(square, {0.0, 1.0}));
  const InsideTest fast(square);
  for (const Point p : {Point{0.5, 0.5}, Point{0, 0.5}, Point{1, 0.5}, Point{0.5, 0}, Point{0.5, 1},
                        Point{-1, 0.5}, Point{2, 0.5}}) {
    EXPECT_EQ(fast(p), is_inside(square, p));
  }
  EXPECT_DOUBLE_EQ(distance_to_polyline(square, {2.0, 0.5}, true), 1.0);
  EXPECT_DOUBLE_EQ(distance_to_polyline(square, {0.5, 0.5}, false), 0.5);
  EXPECT_FALSE(find_self_intersection(square).has_value());
  EXPECT_TRUE(find_self_intersection({{0, 0}, {1, 1}, {1, 0}, {0, 1}}).has_value());  // bow tie
  EXPECT_TRUE(find_self_intersection({{0, 0}, {2, 0}, {1, 0}, {1, 1}}).has_value());  // fold
}

TEST(GearGeometry, LatticeFillMatchesThePointTestAndTheArea) {
  const PinionGeometry g(pinion_spec(12, 4e-3, 20.0, 0.0));
  const RackGeometry rack{RackSpec{}};
  const std::vector<Polygon> bodies{g.sector_outline(-1, 1, 10e-3), g.outline(), rack.outline()};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const Polygon& body : bodies) {
    const InsideTest inside(body);
    const Box box = bounding_box(body);
    for (const double dx : {1e-3, 0.37e-3, 0.25e-3}) {
      const Point origin{dx * unit(rng), dx * unit(rng)};
      const std::vector<Point> pts = fill_lattice(body, dx, origin);
      // Cell volumes dx^2 tile the body up to its boundary strip.
      const double area = signed_area(body), bound = perimeter(body) * dx / 2.0;
      EXPECT_NEAR(static_cast<double>(pts.size()) * dx * dx, area, bound) << dx;
      // Exactly the lattice points the inside tests accept.
      std::size_t count = 0;
      const long a0 = std::lround((box.lo.x - origin.x) / dx) - 2;
      const long a1 = std::lround((box.hi.x - origin.x) / dx) + 2;
      const long b0 = std::lround((box.lo.y - origin.y) / dx) - 2;
      const long b1 = std::lround((box.hi.y - origin.y) / dx) + 2;
      for (long b = b0; b <= b1; ++b) {
        for (long a = a0; a <= a1; ++a) {
          const Point q = lattice_point(origin, dx, a, b);
          const bool in = inside(q);
          if (dx > 0.5e-3) {
            ASSERT_EQ(in, is_inside(body, q));
          }
          count += in;
        }
      }
      EXPECT_EQ(count, pts.size());
    }
  }
}

using PointSet = std::set<std::pair<double, double>>;

PointSet as_set(const std::vector<Point>& pts) {
  PointSet s;
  for (const Point& p : pts) s.insert({p.x, p.y});
  return s;
}

// The pieces' fills are disjoint and together equal the fill of the whole.
void expect_partition(const Polygon& whole, const std::vector<Polygon>& pieces, double dx,
                      Point origin) {
  const PointSet all = as_set(fill_lattice(whole, dx, origin));
  PointSet seen;
  std::size_t total = 0;
  for (const Polygon& piece : pieces) {
    const auto pts = fill_lattice(piece, dx, origin);
    total += pts.size();
    for (const Point& p : pts) EXPECT_TRUE(seen.insert({p.x, p.y}).second) << "claimed twice";
  }
  EXPECT_EQ(total, all.size());
  EXPECT_EQ(seen, all);
}

TEST(GearGeometry, BodiesSharingAnEdgeNeverClaimTheSamePoint) {
  const double dx = 1e-3;
  // Edges through rows and columns of lattice points: a square cut along its
  // diagonal and along a lattice column.
  const double lo = 0.5 * dx, hi = 10.5 * dx, mid = 5.5 * dx;
  const Polygon square{{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}};
  const Polygon below{{lo, lo}, {hi, lo}, {hi, hi}}, above{{lo, lo}, {hi, hi}, {lo, hi}};
  expect_partition(square, {below, above}, dx, {0.0, 0.0});
  const Polygon left{{lo, lo}, {mid, lo}, {mid, hi}, {lo, hi}};
  const Polygon right{{mid, lo}, {hi, lo}, {hi, hi}, {mid, hi}};
  expect_partition(square, {left, right}, dx, {0.0, 0.0});
  // The gear as twelve single-tooth pie slices (all meeting at the centre,
  // which is a lattice point for the second origin), and as a sector plus
  // its complement around a bore.
  const PinionGeometry g(pinion_spec(12, 4e-3, 20.0, 0.0));
  std::vector<Polygon> pies;
  for (int k = 0; k < 12; ++k) pies.push_back(g.sector_outline(k, k, 0.0));
  for (const Point origin :
       {Point{0.0, 0.0}, Point{-0.5 * dx, -0.5 * dx}, Point{0.3 * dx, 0.1 * dx}}) {
    expect_partition(g.outline(), pies, dx, origin);
  }
  const double bore = 10e-3;
  std::vector<Polygon> halves{g.sector_outline(-1, 1, bore), g.sector_outline(2, 10, bore)};
  PointSet union_of_halves;
  std::size_t total = 0;
  for (const Polygon& h : halves) {
    const auto pts = fill_lattice(h, 0.5 * dx, {0.0, 0.0});
    total += pts.size();
    for (const Point& p : pts) union_of_halves.insert({p.x, p.y});
  }
  EXPECT_EQ(total, union_of_halves.size());
  // Together they are the gear outside the bore.
  std::size_t outside_bore = 0;
  for (const Point& p : fill_lattice(g.outline(), 0.5 * dx, {0.0, 0.0}))
    outside_bore += norm(p) > bore + 1e-9;
  EXPECT_EQ(total, outside_bore);
}

// ---------------------------------------------------------------------------
// SVG

// Tags balance and attribute quotes pair up (enough to catch a broken writer).
bool well_formed(const std::string& xml, std::string& why) {
  std::vector<std::string> open;
  std::size_t pos = 0;
  while ((pos = xml.find('<', pos)) != std::string::npos) {
    if (xml.compare(pos, 2, "<?") == 0) {
      pos = xml.find("?>", pos);
      if (pos == std::string::npos) return why = "unterminated prolog", false;
      continue;
    }
    const std::size_t end = xml.find('>', pos);
    if (end == std::string::npos) return why = "unterminated tag", false;
    const std::string tag = xml.substr(pos + 1, end - pos - 1);
    if (std::count(tag.begin(), tag.end(), '"') % 2 != 0) return why = "quotes in " + tag, false;
    if (tag.front() == '/') {
      if (open.empty() || open.back() != tag.substr(1)) return why = "stray " + tag, false;
      open.pop_back();
    } else if (tag.back() != '/') {
      open.push_back(tag.substr(0, tag.find(' ')));
    }
    pos = end + 1;
  }
  if (!open.empty()) return why = "unclosed " + open.back(), false;
  return true;
}

TEST(GearGeometry, SvgPictureIsWrittenAndWellFormed) {
  const PinionGeometry g(pinion_spec(12, 4e-3, 20.0, 0.0));
  const RackGeometry rack{RackSpec{}};
  const MeshPlacement mp = place_in_mesh(g, rack, {0.0, 0.0}, 0, 2, 0.0);
  const Polygon pw = transformed(g.sector_outline(-1, 1, 10e-3), mp.pinion);
  const Polygon rw = transformed(rack.outline(), mp.rack);
  SvgDrawing d;
  d.title = "z = 12 pinion sector & rack <test>";
  d.lines.push_back({pw, "#c00000", true, 1.0});
  d.lines.push_back({rw, "#0000c0", true, 1.0});
  d.dots.push_back({fill_lattice(pw, 1e-3, {0.0, 0.0}), "#c00000", 0.3e-3});
  d.dots.push_back({fill_lattice(rw, 1e-3, {0.0, 0.0}), "#0000c0", 0.0});
  const std::string path = ::testing::TempDir() + "gear_geometry_test.svg";
  write_svg(path, d);
  std::ifstream in(path);
  ASSERT_TRUE(in.good());
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string xml = buffer.str();
  std::string why;
  EXPECT_TRUE(well_formed(xml, why)) << why;
  EXPECT_EQ(xml.rfind("<?xml", 0), 0u);
  EXPECT_NE(xml.find("<svg xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  EXPECT_NE(xml.find("&lt;test&gt;"), std::string::npos);  // title escaped
  EXPECT_NE(xml.find(" mm</text>"), std::string::npos);    // scale bar
  std::size_t circles = 0;
  for (std::size_t pos = 0; (pos = xml.find("<circle", pos)) != std::string::npos; ++pos) ++circles;
  EXPECT_EQ(circles, d.dots[0].points.size() + d.dots[1].points.size());
  EXPECT_THROW(write_svg("/nonexistent-dir/x.svg", d), std::runtime_error);
}

}  // namespace
}  // namespace gearsph::geometry
