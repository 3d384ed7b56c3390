#include "solver/gear/fillet.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace gearsph::gear {

namespace {

using geometry::at_arc;
using geometry::Point;
constexpr double kPi = std::numbers::pi;

// The right half tooth of the generating frame (axis +y) from the space
// centre to the tip, with a vertex exactly on the form circle, where the
// fillet ends.
struct HalfTooth {
  std::vector<Point> line;
  std::vector<double> cum;      // arc length at each vertex
  std::size_t form_vertex = 0;  // the vertex on the form circle
};

HalfTooth half_tooth_line(const geometry::PinionGeometry& g) {
  const std::vector<Point>& half = g.half_tooth();
  const double r_end = g.form_radius();
  HalfTooth h;
  h.line.push_back(half.front());
  bool cut = false;
  for (std::size_t k = 1; k < half.size(); ++k) {
    const double r0 = geometry::norm(half[k - 1]), r1 = geometry::norm(half[k]);
    if (!cut && r1 >= r_end) {
      const double f = r1 > r0 ? std::clamp((r_end - r0) / (r1 - r0), 0.0, 1.0) : 1.0;
      h.line.push_back(half[k - 1] + f * (half[k] - half[k - 1]));
      h.form_vertex = h.line.size() - 1;
      cut = true;
    }
    if (geometry::norm(half[k] - h.line.back()) > 0.0) h.line.push_back(half[k]);
  }
  if (!cut) throw std::runtime_error("fillet: the half tooth never reaches the form circle");
  h.cum = geometry::cumulative_arc(h.line);
  return h;
}

// Length of the polyline segment at arc length s.
double segment_at(const std::vector<double>& cum, double s) {
  const auto it = std::upper_bound(cum.begin(), cum.end(), std::clamp(s, 0.0, cum.back()));
  const std::size_t k =
      std::min<std::size_t>(std::max<std::ptrdiff_t>(it - cum.begin(), 1), cum.size() - 1);
  return cum[k] - cum[k - 1];
}

// The fillet in the generating frame, right side, resampled every `step`,
// with `reach` of outline beyond either end.
FilletCurve generating_curve(const geometry::PinionGeometry& g, double step, double reach) {
  const HalfTooth h = half_tooth_line(g);
  const std::size_t end = h.form_vertex + 1;
  const std::vector<Point> line(h.line.begin(), h.line.begin() + end);
  const std::vector<double> cum(h.cum.begin(), h.cum.begin() + end);
  const double length = cum.back();
  const std::size_t n =
      std::max<std::size_t>(3, static_cast<std::size_t>(std::ceil(length / step)) + 1);
  const double ds = length / static_cast<double>(n - 1);
  // Tangents by a central difference over a chord that reaches past the
  // polyline's vertices on either side: inside one of its segments the
  // direction would be that segment's, a staircase in steps of about 0.6
  // degrees on the fillet (segments of ~30 um at 0.1 um chord error), which
  // moves ISO's 30-degree point by up to half a segment.
  FilletCurve c;
  for (std::size_t i = 0; i < n; ++i) {
    const double s = ds * static_cast<double>(i);
    const Point p = at_arc(line, cum, s);
    const double delta = std::max(0.1 * ds, 1.5 * segment_at(cum, s));
    const Point d = at_arc(line, cum, s + delta) - at_arc(line, cum, s - delta);
    const Point t = (1.0 / geometry::norm(d)) * d;
    c.points.push_back(p);
    c.tangent.push_back(t);
    c.normal.push_back({t.y, -t.x});  // the walk is counter-clockwise round the gear
    c.arc.push_back(s);
  }
  // The tooth space is symmetric about the radial line through its centre:
  // past it lies this fillet's mirror image.
  const Point u = (1.0 / geometry::norm(line.front())) * line.front();
  const std::size_t beyond = static_cast<std::size_t>(std::ceil(reach / ds));
  for (std::size_t j = 1; j <= beyond; ++j) {
    const double s = ds * static_cast<double>(j);
    const Point q = at_arc(h.line, h.cum, s);
    c.before.push_back(2.0 * geometry::dot(q, u) * u - q);
    c.after.push_back(at_arc(h.line, h.cum, length + s));
  }
  return c;
}

FilletCurve placed(const FilletCurve& gen, bool mirror, double to_gear,
                   const geometry::Transform& placement) {
  FilletCurve c;
  const double turn = to_gear + placement.angle;
  auto flip = [mirror](Point p) { return mirror ? Point{-p.x, p.y} : p; };
  const Point centre = placement.apply({0.0, 0.0});
  for (std::size_t i = 0; i < gen.size(); ++i) {
    const Point p = placement.apply(geometry::rotate(flip(gen.points[i]), to_gear));
    const Point t = geometry::rotate(flip(gen.tangent[i]), turn);
    c.points.push_back(p);
    c.tangent.push_back(t);
    c.normal.push_back(geometry::rotate(flip(gen.normal[i]), turn));
    c.arc.push_back(gen.arc[i]);
    c.radius.push_back(geometry::norm(p - centre));
    // Frame-independent: measured in the generating frame (axis +y).
    c.tangent_angle.push_back(std::atan2(std::abs(gen.tangent[i].x), std::abs(gen.tangent[i].y)));
  }
  for (const Point& p : gen.before)
    c.before.push_back(placement.apply(geometry::rotate(flip(p), to_gear)));
  for (const Point& p : gen.after)
    c.after.push_back(placement.apply(geometry::rotate(flip(p), to_gear)));
  // ISO's point: the tangent angle falls through 30 degrees once on the way up.
  const double target = kPi / 6.0;
  c.i30 = c.size() - 2;
  c.f30 = 1.0;
  for (std::size_t i = 0; i + 1 < c.size(); ++i) {
    const double a0 = c.tangent_angle[i], a1 = c.tangent_angle[i + 1];
    if (a0 >= target && a1 <= target) {
      c.i30 = i;
      c.f30 = a0 > a1 ? (a0 - target) / (a0 - a1) : 0.0;
      break;
    }
  }
  return c;
}

double at_fraction(const std::vector<double>& v, std::size_t i, double f) {
  return v[i] + f * (v[i + 1] - v[i]);
}

// The extreme of `v` (largest of sign * v), refined by a parabola through it
// and its neighbours when it is not at an end.
FilletPeak peak_of(const FilletCurve& c, const std::vector<double>& v, double sign) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < v.size(); ++i) {
    if (sign * v[i] > sign * v[best]) best = i;
  }
  FilletPeak p;
  p.stress_Pa = v[best];
  p.arc_m = c.arc[best];
  p.radius_m = c.radius[best];
  p.angle_rad = c.tangent_angle[best];
  if (best > 0 && best + 1 < v.size()) {
    const double a = v[best - 1], b = v[best], d = v[best + 1];
    const double curvature = a - 2.0 * b + d;
    if (sign * curvature < 0.0) {
      const double u = std::clamp(0.5 * (a - d) / curvature, -0.5, 0.5);  // in samples
      p.stress_Pa = b - 0.25 * (a - d) * u;
      const std::size_t j = u >= 0.0 ? best : best - 1;
      const double f = u >= 0.0 ? u : 1.0 + u;
      p.arc_m = at_fraction(c.arc, j, f);
      p.radius_m = at_fraction(c.radius, j, f);
      p.angle_rad = at_fraction(c.tangent_angle, j, f);
    }
  }
  p.at_iso30_Pa = at_fraction(v, c.i30, c.f30);
  return p;
}

}  // namespace

std::vector<Point> with_reach(const FilletCurve& c, std::vector<double>* arc) {
  const double ds = c.arc[1] - c.arc[0];
  std::vector<Point> out(c.before.rbegin(), c.before.rend());
  out.insert(out.end(), c.points.begin(), c.points.end());
  out.insert(out.end(), c.after.begin(), c.after.end());
  if (arc) {
    arc->clear();
    for (std::size_t j = c.before.size(); j > 0; --j) arc->push_back(-ds * static_cast<double>(j));
    arc->insert(arc->end(), c.arc.begin(), c.arc.end());
    for (std::size_t j = 1; j <= c.after.size(); ++j) {
      arc->push_back(c.arc.back() + ds * static_cast<double>(j));
    }
  }
  return out;
}

ToothFillets tooth_fillets(const geometry::PinionGeometry& pinion, int k,
                           const geometry::Transform& placement, Point load_direction, double step,
                           double reach) {
  if (!(step > 0.0)) throw std::invalid_argument("fillet: the sampling step must be positive");
  if (!(reach >= 0.0)) throw std::invalid_argument("fillet: the reach must not be negative");
  const FilletCurve gen = generating_curve(pinion, step, reach);
  const double to_gear = kPi + k * pinion.angular_pitch();
  FilletCurve right = placed(gen, false, to_gear, placement);
  FilletCurve left = placed(gen, true, to_gear, placement);
  // The loaded flank faces the force: its outward normal (at the foot of the
  // flank, the end of the fillet) points against it.
  const bool right_loaded = geometry::dot(right.normal.back(), load_direction) <
                            geometry::dot(left.normal.back(), load_direction);
  ToothFillets f;
  f.tooth = k;
  f.centre = placement.apply({0.0, 0.0});
  f.tension = right_loaded ? std::move(right) : std::move(left);
  f.compression = right_loaded ? std::move(left) : std::move(right);
  return f;
}

std::vector<Point> loaded_flank(const geometry::PinionGeometry& pinion, int k,
                                const geometry::Transform& placement, Point load_direction) {
  // The side comes from the fillets' flank-foot normals (tooth_fillets).
  const ToothFillets f =
      tooth_fillets(pinion, k, placement, load_direction, 1e-3 * pinion.spec().tool.module_m);
  const double to_gear = kPi + k * pinion.angular_pitch();
  const Point foot = f.tension.points.back();
  std::vector<Point> right, left;
  for (const Point& q : pinion.half_tooth()) {
    if (geometry::norm(q) < pinion.form_radius()) continue;
    right.push_back(placement.apply(geometry::rotate(q, to_gear)));
    left.push_back(placement.apply(geometry::rotate({-q.x, q.y}, to_gear)));
  }
  // The tension fillet ends at the foot of the loaded flank.
  return geometry::norm(right.front() - foot) < geometry::norm(left.front() - foot) ? right : left;
}

std::array<double, 4> tooth_window(const ToothFillets& f, double tip_radius) {
  const Point a = f.tension.points.front() - f.centre;
  const Point b = f.compression.points.front() - f.centre;
  // The tooth axis bisects the two space centres (half a pitch either side).
  const Point sum = (1.0 / geometry::norm(a)) * a + (1.0 / geometry::norm(b)) * b;
  const Point u = (1.0 / geometry::norm(sum)) * sum, v{-u.y, u.x};
  const double half = 1.15 * std::max(std::abs(geometry::dot(a, v)), std::abs(geometry::dot(b, v)));
  const double space = std::min(geometry::dot(a, u), geometry::dot(b, u));
  const double height = tip_radius - space;
  const double inner = space - 0.25 * height, outer = tip_radius + 0.04 * height;
  // The rectangle's size whatever way the tooth is turned (a figure of it
  // keeps the scale of an upright one), centred on it ...
  const Point mid = f.centre + (0.5 * (inner + outer)) * u;
  const double half_height = 0.5 * (outer - inner);
  std::array<double, 4> box{mid.x - half, mid.y - half_height, mid.x + half, mid.y + half_height};
  // ... and grown where a turned tooth's fillets or tip would leave it.
  auto hold = [&box](Point p) {
    box = {std::min(box[0], p.x), std::min(box[1], p.y), std::max(box[2], p.x),
           std::max(box[3], p.y)};
  };
  for (const FilletCurve* c : {&f.tension, &f.compression}) {
    for (const Point& p : c->points) hold(p);
  }
  hold(f.centre + tip_radius * u);
  return box;
}

double PlaneStress::max_principal() const {
  return 0.5 * (xx + yy) + std::sqrt(0.25 * (xx - yy) * (xx - yy) + xy * xy);
}

double PlaneStress::min_principal() const {
  return 0.5 * (xx + yy) - std::sqrt(0.25 * (xx - yy) * (xx - yy) + xy * xy);
}

double PlaneStress::along(Point t) const {
  return t.x * t.x * xx + 2.0 * t.x * t.y * xy + t.y * t.y * yy;
}

namespace {

// The peaks of the two curves, one value per sample of each fillet.
FilletStress from_curves(const ToothFillets& f, std::vector<double> tension,
                         std::vector<double> compression) {
  if (tension.size() != f.tension.size() || compression.size() != f.compression.size()) {
    throw std::invalid_argument("fillet_stress: one stress per fillet sample");
  }
  FilletStress out;
  out.tension = peak_of(f.tension, tension, 1.0);
  out.compression = peak_of(f.compression, compression, -1.0);
  out.tension_curve = std::move(tension);
  out.compression_curve = std::move(compression);
  return out;
}

}  // namespace

FilletStress fillet_stress(const ToothFillets& f, const std::vector<PlaneStress>& tension_stress,
                           const std::vector<PlaneStress>& compression_stress) {
  std::vector<double> tension, compression;
  for (const PlaneStress& s : tension_stress) tension.push_back(s.max_principal());
  for (const PlaneStress& s : compression_stress) compression.push_back(s.min_principal());
  return from_curves(f, std::move(tension), std::move(compression));
}

FilletStress fillet_stress(const ToothFillets& f, const std::vector<double>& tension_tangential,
                           const std::vector<double>& compression_tangential) {
  std::vector<double> tension, compression;
  for (double s : tension_tangential) tension.push_back(std::max(s, 0.0));
  for (double s : compression_tangential) compression.push_back(std::min(s, 0.0));
  return from_curves(f, std::move(tension), std::move(compression));
}

}  // namespace gearsph::gear
