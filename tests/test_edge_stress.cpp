// The stress along a boundary from its own stretch (diagnostics/edge_stress):
// exact for the displacement fields a quadratic fit holds, blind to rigid
// rotations of any size, and Hooke's law in plane strain with the known
// normal stress.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/diagnostics/edge_stress.hpp"

namespace gearsph {
namespace {

using diagnostics::EdgeCurve;
using geometry::Point;

constexpr double kE = 2e11, kNu = 0.3;
const double kPlane = kE / (1.0 - kNu * kNu);

EdgeCurve circle(double a, int n) {
  EdgeCurve c;
  c.closed = true;
  for (int k = 0; k < n; ++k) {
    const double t = 2.0 * std::numbers::pi * k / n;
    c.reference.push_back({a * std::cos(t), a * std::sin(t)});
    c.arc.push_back(a * t);
  }
  return c;
}

TEST(EdgeStress, UniformStretchOfAHoleGivesPlaneStrainHooke) {
  EdgeCurve c = circle(4e-3, 360);
  const double eps = 1e-4;
  for (const Point X : c.reference) c.displacement.push_back(eps * X);
  const std::vector<double> free = edge_tangential_stress(c, 0.5e-3, kE, kNu);
  // A circle stretched by eps: the tangential strain is eps (to eps^2).
  for (double s : free) EXPECT_NEAR(s / (kPlane * eps), 1.0, 1e-4);
  // With a known normal stress (a pressure p on a bore: sigma_nn = -p).
  const std::vector<double> snn(c.reference.size(), -50e6);
  const std::vector<double> pressed = edge_tangential_stress(c, 0.5e-3, kE, kNu, &snn);
  for (std::size_t k = 0; k < pressed.size(); ++k) {
    EXPECT_NEAR(pressed[k], free[k] + kNu / (1.0 - kNu) * -50e6, 1e-6 * kPlane * eps);
  }
}

TEST(EdgeStress, RigidRotationOfAnySizeGivesNoStress) {
  EdgeCurve c = circle(4e-3, 360);
  const double angle = 0.6;  // radians: far beyond a small rotation
  const double cs = std::cos(angle), sn = std::sin(angle);
  for (const Point X : c.reference) {
    const Point x{cs * X.x - sn * X.y + 1e-3, sn * X.x + cs * X.y - 2e-3};
    c.displacement.push_back(x - X);
  }
  for (double s : edge_tangential_stress(c, 0.5e-3, kE, kNu)) EXPECT_NEAR(s, 0.0, 1e-9 * kE);
}

TEST(EdgeStress, VaryingStretchAlongAnOpenCurveEndsIncluded) {
  // A straight edge along x with u_x = b x^2 / 2: eps(x) = b x, read exactly
  // by the quadratic fit, at the ends (one-sided windows) too.
  EdgeCurve c;
  const double b = 0.05;  // strain per metre
  for (int k = 0; k <= 100; ++k) {
    const double x = 1e-3 * k / 100.0;
    c.reference.push_back({x, 0.0});
    c.arc.push_back(x);
    c.displacement.push_back({0.5 * b * x * x, 1e-6 * x});  // and a small rotation
  }
  const std::vector<double> s = edge_tangential_stress(c, 0.1e-3, kE, kNu);
  for (std::size_t k = 0; k < s.size(); ++k) {
    const double x = c.arc[k];
    // The rotation adds (1e-6)^2 / 2 to the stretch: negligible here.
    EXPECT_NEAR(s[k], kPlane * b * x, 1e-3 * kPlane * b * 1e-3) << "at x = " << x;
  }
}

TEST(EdgeStress, RefusesWhatItCannotFit) {
  EdgeCurve c = circle(4e-3, 36);
  for (const Point X : c.reference) c.displacement.push_back(1e-4 * X);
  EXPECT_THROW(edge_tangential_stress(c, 1e-9, kE, kNu), std::invalid_argument);
  c.displacement.pop_back();
  EXPECT_THROW(edge_tangential_stress(c, 0.5e-3, kE, kNu), std::invalid_argument);
}

}  // namespace
}  // namespace gearsph
