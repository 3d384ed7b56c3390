#include "solver/geometry/polygon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gearsph::geometry {

double norm(Point a) {
  return std::hypot(a.x, a.y);
}

Point rotate(Point a, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * a.x - s * a.y, s * a.x + c * a.y};
}

Polygon transformed(const Polygon& poly, const Transform& t) {
  Polygon out;
  out.reserve(poly.size());
  for (const Point& p : poly) out.push_back(t.apply(p));
  return out;
}

Box bounding_box(const std::vector<Point>& points) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Box b{{inf, inf}, {-inf, -inf}};
  for (const Point& p : points) {
    b.lo = {std::min(b.lo.x, p.x), std::min(b.lo.y, p.y)};
    b.hi = {std::max(b.hi.x, p.x), std::max(b.hi.y, p.y)};
  }
  return b;
}

double signed_area(const Polygon& poly) {
  double twice = 0.0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) twice += cross(poly[i], poly[(i + 1) % n]);
  return 0.5 * twice;
}

double polar_moment(const Polygon& poly) {
  double twelve = 0.0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    const Point a = poly[i], b = poly[(i + 1) % n];
    twelve += cross(a, b) * (a.x * a.x + a.x * b.x + b.x * b.x + a.y * a.y + a.y * b.y + b.y * b.y);
  }
  return twelve / 12.0;
}

double perimeter(const Polygon& poly) {
  double length = 0.0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) length += norm(poly[(i + 1) % n] - poly[i]);
  return length;
}

static double distance_to_segment(Point a, Point b, Point p) {
  const Point ab = b - a;
  const double len2 = dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return norm(p - (a + t * ab));
}

std::vector<double> cumulative_arc(const std::vector<Point>& line) {
  std::vector<double> cum(line.size(), 0.0);
  for (std::size_t k = 1; k < line.size(); ++k) {
    cum[k] = cum[k - 1] + norm(line[k] - line[k - 1]);
  }
  return cum;
}

Point at_arc(const std::vector<Point>& line, const std::vector<double>& cum, double s) {
  s = std::clamp(s, 0.0, cum.back());
  const auto it = std::upper_bound(cum.begin(), cum.end(), s);
  const std::size_t k =
      std::min<std::size_t>(std::max<std::ptrdiff_t>(it - cum.begin(), 1), line.size() - 1);
  const double len = cum[k] - cum[k - 1];
  const double f = len > 0.0 ? (s - cum[k - 1]) / len : 0.0;
  return line[k - 1] + f * (line[k] - line[k - 1]);
}

double distance_to_polyline(const std::vector<Point>& line, Point p, bool closed) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = line.size();
  if (n == 1) return norm(p - line[0]);
  const std::size_t segments = closed ? n : n - 1;
  for (std::size_t i = 0; i < segments; ++i) {
    best = std::min(best, distance_to_segment(line[i], line[(i + 1) % n], p));
  }
  return best;
}

// Kept out of line on purpose: every caller must get bit-identical abscissae
// for the same edge (no caller-dependent FMA contraction), which is what makes
// the shared-edge rule exact.
[[gnu::noinline]] bool edge_crossing(Point a, Point b, double y, double& x_cross) {
  if (a.y == b.y) return false;
  const Point lo = a.y < b.y ? a : b;
  const Point hi = a.y < b.y ? b : a;
  if (!(lo.y <= y && y < hi.y)) return false;
  x_cross = lo.x + (y - lo.y) * (hi.x - lo.x) / (hi.y - lo.y);
  return true;
}

bool is_inside(const Polygon& poly, Point p) {
  const Box b = bounding_box(poly);
  if (p.x < b.lo.x || p.x > b.hi.x || p.y < b.lo.y || p.y > b.hi.y) return false;
  bool inside = false;
  double xc = 0.0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    if (edge_crossing(poly[i], poly[(i + 1) % n], p.y, xc) && xc > p.x) inside = !inside;
  }
  return inside;
}

double shortest_edge(const Polygon& poly) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    best = std::min(best, norm(poly[(i + 1) % n] - poly[i]));
  }
  return best;
}

}  // namespace gearsph::geometry
