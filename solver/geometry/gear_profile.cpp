#include "solver/geometry/gear_profile.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "solver/geometry/curve_sampling.hpp"
#include "solver/geometry/rack_cutter.hpp"

namespace gearsph::geometry {

namespace {

constexpr double kPi = std::numbers::pi;
// Vertices closer than this (0.1 nm) are one vertex.
constexpr double kSameVertex = 1e-10;

double involute(double a) {
  return std::tan(a) - a;
}

// Point at half angle psi from the +y axis (towards +x) on a circle.
auto circle(double radius) {
  return [radius](double psi) { return Point{radius * std::sin(psi), radius * std::cos(psi)}; };
}

void drop_repeats(std::vector<Point>& points) {
  std::vector<Point> kept;
  for (const Point& p : points) {
    if (kept.empty() || norm(p - kept.back()) >= kSameVertex) kept.push_back(p);
  }
  points.swap(kept);
}

// Half angle of a generating-frame point from the tooth axis (+y).
double half_angle(Point p) {
  return std::atan2(p.x, p.y);
}

}  // namespace

PinionGeometry::PinionGeometry(const PinionSpec& spec) : spec_(spec) {
  const BasicRack& tool = spec_.tool;
  const double m = tool.module_m, alpha = tool.pressure_angle_rad, x = spec_.profile_shift;
  r_ = m * spec_.teeth / 2.0;
  rb_ = r_ * std::cos(alpha);
  ra_ = r_ + tool.addendum() + x * m;
  rf_ = r_ - tool.dedendum() + x * m;
  s_ = m * (kPi / 2.0 + 2.0 * x * std::tan(alpha)) - spec_.backlash_m;
  validate();

  const RackCutter cutter(tool, r_, x, spec_.backlash_m);
  undercut_ = cutter.ell_round() < 0.0;
  // Not undercut: the flank starts where the round meets it, on the
  // generated root form circle (ISO 21771:2007, d_Ff for a rack-type tool).
  const FlankStart start =
      undercut_ ? undercut_start(cutter) : FlankStart{cutter.theta_flank(), cutter.ell_round()};
  r_form_ = std::hypot(rb_, start.ell);
  if (!(r_form_ < ra_)) throw std::invalid_argument("pinion: fillet reaches the tip circle");
  build_half_tooth(cutter, start);
}

void PinionGeometry::validate() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("pinion: " + what); };
  if (spec_.teeth < 3) fail("needs at least 3 teeth");
  if (!(spec_.backlash_m >= 0.0)) fail("backlash allowance must not be negative");
  if (!(spec_.chord_tolerance_m > 0.0)) fail("chord tolerance must be positive");
  spec_.tool.validate(spec_.backlash_m);
  if (!(rf_ > 0.0)) fail("root circle radius is not positive (too few teeth for this shift)");
  if (!(s_ > 0.0)) fail("backlash allowance leaves no tooth at the pitch circle");
  if (!(involute_half_angle(ra_) > 0.0))
    fail("pointed tooth: the flanks meet below the tip circle");
}

double PinionGeometry::involute_half_angle(double radius) const {
  const double alpha_y = std::acos(std::min(1.0, rb_ / radius));
  return s_ / (2.0 * r_) + involute(spec_.tool.pressure_angle_rad) - involute(alpha_y);
}

// Walks down the fillet from the round/flank junction, which (undercut) lies on
// the involute's second branch outside the tooth, to the first point that is
// no longer outside the involute:
//  - the fillet crosses the involute above the base circle: the undercut
//    point, where the involute now begins;
//  - the fillet dips below the base circle first (only within a hair of the
//    undercut limit): the involute keeps its foot, the fillet continues below
//    the base circle, and the outline steps along the base circle to the cusp
//    (a step of the order of the remaining branch length, far below 1 um).
// Below the base circle the involute is continued by its radial cusp line so
// that the gap is continuous for the bisection.
PinionGeometry::FlankStart PinionGeometry::undercut_start(const RackCutter& cutter) const {
  auto radius = [&](double theta) { return norm(cutter.fillet_point(theta)); };
  auto gap = [&](double theta) {
    const Point g = cutter.fillet_point(theta);
    return half_angle(g) - involute_half_angle(std::max(norm(g), rb_));
  };
  auto bisect = [](double out, double in, auto&& is_out) {
    for (int i = 0; i < 200 && std::abs(in - out) > 1e-15; ++i) {
      const double mid = 0.5 * (out + in);
      (is_out(mid) ? out : in) = mid;
    }
    return in;
  };
  constexpr int kScan = 4096;
  const double t0 = cutter.theta_flank(), t1 = 1.5 * kPi;
  double prev = t0;
  for (int i = 1; i <= kScan; ++i) {
    const double t = t0 + (t1 - t0) * i / kScan;
    const bool crossed = gap(t) <= 0.0;
    if (!crossed && radius(t) >= rb_) {
      prev = t;
      continue;
    }
    const double cut = crossed ? bisect(prev, t, [&](double u) { return gap(u) > 0.0; }) : t;
    const double r_cut = radius(cut);
    if (crossed && r_cut >= rb_) return {cut, std::sqrt(r_cut * r_cut - rb_ * rb_)};
    return {bisect(prev, cut, [&](double u) { return radius(u) >= rb_; }), 0.0};
  }
  throw std::logic_error("pinion: undercut fillet never meets the involute");
}

void PinionGeometry::build_half_tooth(const RackCutter& cutter, FlankStart start) {
  const double tol = spec_.chord_tolerance_m;
  half_.clear();
  const double psi_space = kPi / spec_.teeth, psi_root = cutter.root_half_angle();
  if (rf_ * (psi_space - psi_root) > tol) {
    sample_curve(circle(rf_), psi_space, psi_root, tol, half_);
  } else {
    half_.push_back(circle(rf_)(psi_space));
  }
  sample_curve([&](double t) { return cutter.fillet_point(t); }, 1.5 * kPi, start.theta, tol,
               half_);
  const double ell_tip = std::sqrt(ra_ * ra_ - rb_ * rb_);
  sample_curve([&](double l) { return cutter.flank_point(l); }, start.ell, ell_tip, tol, half_);
  const double psi_tip = involute_half_angle(ra_);
  sample_curve(circle(ra_), psi_tip, 0.0, tol, half_);
  // Pieces meet to rounding (or, at the undercut limit, to a sub-nanometre
  // step); drop vertices that repeat their predecessor.
  drop_repeats(half_);
}

double PinionGeometry::angular_pitch() const {
  return 2.0 * kPi / spec_.teeth;
}

double PinionGeometry::tooth_centre_angle(int k) const {
  return -kPi / 2.0 + angular_pitch() * k;
}

double PinionGeometry::cut_angle(int j) const {
  return -kPi / 2.0 + (2.0 * j - 1.0) * kPi / spec_.teeth;
}

int PinionGeometry::wrapped(int j) const {
  return ((j % spec_.teeth) + spec_.teeth) % spec_.teeth;
}

// Index taken modulo z, so that the cut after tooth z - 1 is bit for bit the
// cut before tooth 0 whichever sector asks for it.
Point PinionGeometry::cut_point(int j, double radius) const {
  const double a = cut_angle(wrapped(j));
  return {radius * std::cos(a), radius * std::sin(a)};
}

// One angular pitch around tooth k, from the cut before it up to (excluding)
// the cut after it: the half tooth, the tip on the axis, the mirrored half.
void PinionGeometry::append_pitch(int k, Polygon& out) const {
  const double turn = tooth_centre_angle(wrapped(k)) - kPi / 2.0;
  const std::size_t first = out.size();
  for (const Point& p : half_) out.push_back(rotate(p, turn));
  out.push_back(rotate({0.0, ra_}, turn));
  for (std::size_t i = half_.size() - 1; i >= 1; --i) {
    out.push_back(rotate({-half_[i].x, half_[i].y}, turn));
  }
  out[first] = cut_point(k, rf_);  // bit-identical with the neighbouring pitch or sector
}

Polygon PinionGeometry::outline() const {
  Polygon out;
  for (int k = 0; k < spec_.teeth; ++k) append_pitch(k, out);
  return out;
}

Polygon PinionGeometry::sector_outline(int first, int last, double inner_radius) const {
  const int count = last - first + 1;
  if (count == spec_.teeth && inner_radius == 0.0) return outline();
  if (count < 1 || count >= spec_.teeth) {
    throw std::invalid_argument("pinion sector: needs 1 to z - 1 teeth");
  }
  if (!(inner_radius >= 0.0 && inner_radius < rf_)) {
    throw std::invalid_argument("pinion sector: inner radius must lie in [0, root radius)");
  }
  Polygon out;
  for (int k = first; k <= last; ++k) append_pitch(k, out);
  out.push_back(cut_point(last + 1, rf_));
  if (inner_radius == 0.0) {
    out.push_back({0.0, 0.0});
    return out;
  }
  const auto arc = [&](double a) {
    return Point{inner_radius * std::cos(a), inner_radius * std::sin(a)};
  };
  const std::size_t arc_start = out.size();
  sample_curve(arc, cut_angle(last + 1), cut_angle(first), spec_.chord_tolerance_m, out);
  out[arc_start] = cut_point(last + 1, inner_radius);
  out.push_back(cut_point(first, inner_radius));
  return out;
}

}  // namespace gearsph::geometry
