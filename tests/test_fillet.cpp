// The root fillets of a tooth as curves (solver/gear/fillet.hpp): they lie on
// the generated outline, their 30-degree point is the one the ISO section
// uses, the tension side is the loaded flank's, and the peak of a stress
// given along them is found where it is.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/gear/fillet.hpp"
#include "solver/gear/gear_rating.hpp"
#include "solver/physics/contact_near_field.hpp"

namespace gearsph::gear {
namespace {

using geometry::Point;
constexpr double kPi = std::numbers::pi;

geometry::PinionGeometry paper_pinion() {
  geometry::PinionSpec s;
  s.teeth = 12;
  s.tool.module_m = 4e-3;
  s.tool.pressure_angle_rad = 20.0 * kPi / 180.0;
  s.backlash_m = 1e-4;
  return geometry::PinionGeometry(s);
}

TEST(Fillet, CurvesLieOnTheOutlineFromTheSpaceCentreToTheFormCircle) {
  const geometry::PinionGeometry g = paper_pinion();
  const geometry::Transform place{0.3, {0.01, -0.02}};
  const ToothFillets f = tooth_fillets(g, 2, place, {1.0, 0.0}, 2e-5);
  const geometry::Polygon outline = geometry::transformed(g.outline(), place);
  for (const FilletCurve* c : {&f.tension, &f.compression}) {
    ASSERT_GT(c->size(), 100u);
    EXPECT_NEAR(c->radius.front(), g.root_radius(), 1e-9);
    EXPECT_NEAR(c->radius.back(), g.form_radius(), 1e-9);
    // At the space centre the tangent is square to the radius there, which
    // is half a pitch (pi / z) from the tooth axis.
    EXPECT_NEAR(c->tangent_angle.front(), 0.5 * kPi - kPi / g.teeth(), 1e-3);
    for (std::size_t i = 0; i < c->size(); i += 7) {
      EXPECT_LT(geometry::distance_to_polyline(outline, c->points[i], true), 1e-7);
      // Outward: the normal points away from the material (a point a little
      // along it is outside the outline, a little against it inside).
      const Point out = c->points[i] + 1e-5 * c->normal[i];
      const Point in = c->points[i] - 1e-5 * c->normal[i];
      EXPECT_FALSE(geometry::is_inside(outline, out)) << i;
      EXPECT_TRUE(geometry::is_inside(outline, in)) << i;
      EXPECT_NEAR(geometry::dot(c->normal[i], c->tangent[i]), 0.0, 1e-12);
    }
    for (std::size_t i = 1; i < c->size(); ++i) EXPECT_GT(c->arc[i], c->arc[i - 1]);
  }
}

TEST(Fillet, ThirtyDegreePointIsTheOneOfTheIsoSection) {
  const geometry::PinionGeometry g = paper_pinion();
  // The reference: the outline's own vertex where its slope passes 30
  // degrees, on an outline sampled to a 0.01 nm chord error (segments of
  // ~0.3 um; at the default 0.1 um they are ~30 um long, and the vertex
  // sits up to half of one from the point).
  geometry::PinionSpec fine = g.spec();
  fine.chord_tolerance_m = 1e-11;
  const ThirtyDegreePoints t30 = thirty_degree_points(geometry::PinionGeometry(fine));
  // Tooth 0 unplaced: generating frame turned by pi (tooth axis -y).
  const ToothFillets f = tooth_fillets(g, 0, {}, {1.0, 0.0}, 1e-5);
  for (const FilletCurve* c : {&f.tension, &f.compression}) {
    const Point p = c->points[c->i30] + c->f30 * (c->points[c->i30 + 1] - c->points[c->i30]);
    // Both 30-degree points have the same radius and the chord s_Fn.
    EXPECT_NEAR(geometry::norm(p), geometry::norm(t30.right), 0.5e-6);
    EXPECT_NEAR(2.0 * std::abs(p.x), t30.chord, 1e-6);
  }
  // The tangent follows the curve, not the outline's straight segments:
  // the point moves by well under a segment when the sampling changes.
  const ToothFillets coarse = tooth_fillets(g, 0, {}, {1.0, 0.0}, 2.5e-5);
  const FilletCurve& c = coarse.tension;
  const Point q = c.points[c.i30] + c.f30 * (c.points[c.i30 + 1] - c.points[c.i30]);
  EXPECT_NEAR(geometry::norm(q), geometry::norm(t30.right), 0.5e-6);
}

TEST(Fillet, TensionSideIsUnderTheFlankTheForcePushes) {
  const geometry::PinionGeometry g = paper_pinion();
  // Tooth 0 points down (-y); a force toward +x pushes into its -x flank.
  const ToothFillets f = tooth_fillets(g, 0, {}, {1.0, 0.0}, 5e-5);
  EXPECT_LT(f.tension.points[f.tension.size() / 2].x, 0.0);
  EXPECT_GT(f.compression.points[f.compression.size() / 2].x, 0.0);
  const ToothFillets r = tooth_fillets(g, 0, {}, {-1.0, 0.0}, 5e-5);
  EXPECT_GT(r.tension.points[r.tension.size() / 2].x, 0.0);
}

TEST(Fillet, PeakOfAGivenStressIsFoundBetweenSamples) {
  const geometry::PinionGeometry g = paper_pinion();
  const ToothFillets f = tooth_fillets(g, 0, {}, {1.0, 0.0}, 1e-4);
  // A tangential stress that is a parabola of arc length, peaking between
  // samples: sigma_t = 100 MPa - k (s - s*)^2, and -60 MPa on the other side.
  const double s_star = 0.37 * f.tension.arc.back() + 0.3e-4;
  auto field = [&](const FilletCurve& c, double peak) {
    std::vector<PlaneStress> out;
    for (std::size_t i = 0; i < c.size(); ++i) {
      const double ds = c.arc[i] - s_star;
      const double st = peak * (1.0 - 1e6 * ds * ds);
      const Point t = c.tangent[i];
      out.push_back({st * t.x * t.x, st * t.y * t.y, st * t.x * t.y});
    }
    return out;
  };
  const FilletStress s = fillet_stress(f, field(f.tension, 100e6), field(f.compression, -60e6));
  EXPECT_NEAR(s.tension.stress_Pa, 100e6, 1e3);
  EXPECT_NEAR(s.tension.arc_m, s_star, 1e-8);
  EXPECT_NEAR(s.compression.stress_Pa, -60e6, 1e3);
  EXPECT_NEAR(s.compression.arc_m, s_star, 1e-8);
  // Along the tangent the tensor gives back sigma_t; the 30-degree value is
  // the curve's value there.
  const std::size_t i = f.tension.i30;
  const double expect =
      s.tension_curve[i] + f.tension.f30 * (s.tension_curve[i + 1] - s.tension_curve[i]);
  EXPECT_DOUBLE_EQ(s.tension.at_iso30_Pa, expect);
  const PlaneStress one{3.0, -1.0, 2.0};
  EXPECT_NEAR(one.max_principal() + one.min_principal(), 2.0, 1e-12);
  EXPECT_NEAR(one.along({1.0, 0.0}), 3.0, 1e-12);
}

TEST(Fillet, ReachContinuesTheOutlinePastTheSpaceCentreAndUpTheFlank) {
  const geometry::PinionGeometry g = paper_pinion();
  const geometry::Transform place{0.3, {0.01, -0.02}};
  const double reach = 1e-3;
  const ToothFillets f = tooth_fillets(g, 2, place, {1.0, 0.0}, 5e-5, reach);
  const geometry::Polygon outline = geometry::transformed(g.outline(), place);
  for (const FilletCurve* c : {&f.tension, &f.compression}) {
    ASSERT_GE(c->before.size(), 20u);
    ASSERT_EQ(c->before.size(), c->after.size());
    std::vector<double> arc;
    const std::vector<Point> all = with_reach(*c, &arc);
    ASSERT_EQ(all.size(), arc.size());
    ASSERT_EQ(all.size(), c->size() + 2 * c->before.size());
    const std::size_t first = c->before.size();
    EXPECT_EQ(all[first].x, c->points.front().x);
    EXPECT_EQ(all[first + c->size() - 1].y, c->points.back().y);
    EXPECT_LE(arc.front(), -reach);
    EXPECT_GE(arc.back(), c->arc.back() + reach);
    const double ds = c->arc[1] - c->arc[0];
    for (std::size_t k = 0; k < all.size(); ++k) {
      // On the outline, in order, a step apart (chords of a curved outline
      // are a little shorter than their arcs).
      EXPECT_LT(geometry::distance_to_polyline(outline, all[k], true), 1e-7) << k;
      if (k == 0) continue;
      EXPECT_NEAR(arc[k] - arc[k - 1], ds, 1e-12) << k;
      EXPECT_NEAR(geometry::norm(all[k] - all[k - 1]), ds, 0.01 * ds) << k;
    }
    // Past the space centre the outline goes down the neighbouring tooth's
    // fillet: the same radii as this fillet's, mirrored.
    for (std::size_t j = 0; j < c->before.size(); ++j) {
      EXPECT_NEAR(geometry::norm(c->before[j] - f.centre), c->radius[j + 1], 1e-9) << j;
    }
    // Up the flank: beyond the form circle, rising.
    EXPECT_GT(geometry::norm(c->after.front() - f.centre), g.form_radius());
    EXPECT_GT(geometry::norm(c->after.back() - f.centre),
              geometry::norm(c->after.front() - f.centre));
  }
  // No reach: the fillets as before.
  const ToothFillets plain = tooth_fillets(g, 2, place, {1.0, 0.0}, 5e-5);
  EXPECT_TRUE(plain.tension.before.empty());
  EXPECT_EQ(plain.tension.points.size(), f.tension.points.size());
  EXPECT_EQ(plain.tension.points[7].x, f.tension.points[7].x);
}

TEST(Fillet, TangentialStressGivesThePrincipalStressesOfAFreeEdge) {
  const geometry::PinionGeometry g = paper_pinion();
  const ToothFillets f = tooth_fillets(g, 0, {}, {1.0, 0.0}, 1e-4);
  // sigma_tt a parabola of arc length through zero: on the free edge
  // sigma_1 is sigma_tt where it pulls, zero where it pushes (sigma_nn).
  const double s_star = 0.6 * f.tension.arc.back() + 0.3e-4;
  auto field = [&](const FilletCurve& c, double peak) {
    std::vector<double> out;
    for (double s : c.arc) out.push_back(peak * (1.0 - 2e6 * (s - s_star) * (s - s_star)));
    return out;
  };
  const std::vector<double> t = field(f.tension, 100e6), k = field(f.compression, -60e6);
  const FilletStress s = fillet_stress(f, t, k);
  EXPECT_NEAR(s.tension.stress_Pa, 100e6, 1e3);
  EXPECT_NEAR(s.tension.arc_m, s_star, 1e-8);
  EXPECT_NEAR(s.compression.stress_Pa, -60e6, 1e3);
  bool clipped = false;
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_EQ(s.tension_curve[i], std::max(t[i], 0.0));
    clipped = clipped || t[i] < 0.0;
  }
  EXPECT_TRUE(clipped);  // the field does change sign on the curve
  for (std::size_t i = 0; i < k.size(); ++i) EXPECT_EQ(s.compression_curve[i], std::min(k[i], 0.0));
  // The same as the tensor sigma_tt t t would give.
  std::vector<PlaneStress> tt, kk;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const Point u = f.tension.tangent[i];
    tt.push_back({t[i] * u.x * u.x, t[i] * u.y * u.y, t[i] * u.x * u.y});
  }
  for (std::size_t i = 0; i < k.size(); ++i) {
    const Point u = f.compression.tangent[i];
    kk.push_back({k[i] * u.x * u.x, k[i] * u.y * u.y, k[i] * u.x * u.y});
  }
  const FilletStress from_tensor = fillet_stress(f, tt, kk);
  EXPECT_NEAR(from_tensor.tension.stress_Pa, s.tension.stress_Pa, 1e-6 * 100e6);
  EXPECT_NEAR(from_tensor.tension.at_iso30_Pa, s.tension.at_iso30_Pa, 1e-6 * 100e6);
  EXPECT_NEAR(from_tensor.compression.stress_Pa, s.compression.stress_Pa, 1e-6 * 60e6);
}

TEST(Fillet, ToothWindowHoldsTheToothFromTipToBelowTheRootAndNoNeighbour) {
  const geometry::PinionGeometry g = paper_pinion();
  const double pitch = kPi * g.spec().tool.module_m;
  // Tooth 0 as a static check places it (turned a little, off the origin),
  // and unplaced as the FE check draws it.
  const ToothFillets upright = tooth_fillets(g, 0, {}, {1.0, 0.0}, 2e-5);
  const auto [ux0, uy0, ux1, uy1] = tooth_window(upright, g.tip_radius());
  for (const geometry::Transform place :
       {geometry::Transform{0.11, {0.003, -0.001}}, geometry::Transform{-0.05, {}},
        geometry::Transform{0.26, {}}, geometry::Transform{}}) {
    const ToothFillets f = tooth_fillets(g, 0, place, {1.0, 0.0}, 2e-5);
    const auto [x0, y0, x1, y1] = tooth_window(f, g.tip_radius());
    auto inside = [&](Point p) { return p.x >= x0 && p.x <= x1 && p.y >= y0 && p.y <= y1; };
    for (const FilletCurve* c : {&f.tension, &f.compression}) {
      for (const Point& p : c->points) EXPECT_TRUE(inside(p)) << p.x << ", " << p.y;
    }
    // The whole outline of tooth 0 (within half a pitch of its axis, which
    // points along -y turned by the placement), tip included; the root
    // circle a little further in too; the neighbours' tips not.
    const Point axis = geometry::rotate({0.0, -1.0}, place.angle);
    const double half_pitch = 0.5 * g.angular_pitch();
    int tooth0 = 0;
    for (const Point& q : geometry::transformed(g.outline(), place)) {
      const Point d = q - f.centre;
      const double from_axis = std::acos(geometry::dot(d, axis) / geometry::norm(d));
      if (from_axis < half_pitch) {
        EXPECT_TRUE(inside(q)) << q.x << ", " << q.y;
        ++tooth0;
      }
    }
    EXPECT_GT(tooth0, 50);
    EXPECT_TRUE(inside(f.centre + (0.95 * g.root_radius()) * axis));
    for (const double side : {-1.0, 1.0}) {
      const Point tip = geometry::rotate(axis, side * g.angular_pitch());
      EXPECT_FALSE(inside(f.centre + g.tip_radius() * tip));
    }
    // About a pitch across and no more than 1.5 pitches either way; turned
    // as a static check turns it (a few degrees), the upright tooth's size.
    EXPECT_GT(x1 - x0, 0.8 * pitch);
    EXPECT_LT(x1 - x0, 1.5 * pitch);
    EXPECT_LT(y1 - y0, 1.5 * pitch);
    if (std::abs(place.angle) < 0.15) {
      EXPECT_NEAR(x1 - x0, ux1 - ux0, 1e-12);
      EXPECT_NEAR(y1 - y0, uy1 - uy0, 1e-12);
    }
  }
  // Unplaced, the rectangle itself: the space centres 15 % inside its
  // sides, 4 % of the tooth height beyond the tip, a quarter below.
  const ToothFillets f = tooth_fillets(g, 0, {}, {1.0, 0.0}, 2e-5);
  const auto [x0, y0, x1, y1] = tooth_window(f, g.tip_radius());
  const Point a = f.tension.points.front();
  const double height = g.tip_radius() + a.y;
  EXPECT_NEAR(x1, 1.15 * std::abs(a.x), 1e-12);
  EXPECT_NEAR(x0, -x1, 1e-12);
  EXPECT_NEAR(y0, -g.tip_radius() - 0.04 * height, 1e-12);
  EXPECT_NEAR(y1, a.y + 0.25 * height, 1e-12);
}

TEST(Fillet, NamedPointsOfThePathOfContactLieInOrderOnTheFlank) {
  const geometry::PinionGeometry g = paper_pinion();
  const ContactPath c = rack_contact_path(g);
  const double lp = path_point_radius(g, c, "lpstc"), hp = path_point_radius(g, c, "hpstc");
  EXPECT_LT(g.form_radius(), lp);
  EXPECT_LT(lp, path_point_radius(g, c, "pitch"));
  EXPECT_LT(path_point_radius(g, c, "pitch"), hp);
  EXPECT_LT(hp, path_point_radius(g, c, "tip"));
  // Along the line of action the single-contact zone is (2 - eps) p_b long.
  const double rb = g.base_radius();
  auto from_T = [rb](double r) { return std::sqrt(r * r - rb * rb); };
  EXPECT_NEAR(from_T(hp) - from_T(lp), (2.0 - c.contact_ratio) * c.base_pitch, 1e-12);
  EXPECT_THROW(path_point_radius(g, c, "root"), std::invalid_argument);
}

}  // namespace
}  // namespace gearsph::gear

namespace gearsph {
namespace {

// ISO 6336-2's nominal contact stress against its textbook factors: steel
// on steel Z_E = 189.8 sqrt(N/mm^2), 20 degrees Z_H = 2.495 (ISO 6336-2
// figure for x = 0, beta = 0), and the Hertz line contact it stands for at
// the pitch point (rack flank flat, pinion flank radius r sin(alpha)).
TEST(ContactStress, IsoSigmaH0IsTheHertzPressureAtThePitchPoint) {
  const double E = 206e9, nu = 0.3, e_star = 1.0 / (2.0 * (1.0 - nu * nu) / E);
  const double alpha = 20.0 * std::numbers::pi / 180.0, d = 0.048, b = 0.02, ft = 1000.0;
  const double z_e = std::sqrt(e_star / std::numbers::pi);
  EXPECT_NEAR(z_e / std::sqrt(1e6), 189.8, 0.1);
  const double z_h = std::sqrt(2.0 / (std::cos(alpha) * std::sin(alpha)));
  EXPECT_NEAR(z_h, 2.495, 0.001);
  const double sigma = gear::iso_sigma_H0(ft, d, b, alpha, e_star);
  EXPECT_NEAR(sigma, z_h * z_e * std::sqrt(ft / (d * b)), 1e-9 * sigma);
  const double load = ft / std::cos(alpha) / b;  // normal force per metre
  const double curvature = 1.0 / (0.5 * d * std::sin(alpha));
  EXPECT_NEAR(physics::hertz_peak_pressure(load, e_star, curvature), sigma, 1e-9 * sigma);
}

}  // namespace
}  // namespace gearsph
