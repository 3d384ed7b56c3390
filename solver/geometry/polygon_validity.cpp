// Simplicity check for outlines (polygon.hpp): sweep and prune on the edges'
// x-intervals, then an exact-orientation segment test on the survivors.
#include <algorithm>
#include <numeric>

#include "solver/geometry/polygon.hpp"

namespace gearsph::geometry {

namespace {

double orient(Point a, Point b, Point c) {
  return cross(b - a, c - a);
}

// c lies on segment ab, given that a, b, c are collinear.
bool within(Point a, Point b, Point c) {
  return std::min(a.x, b.x) <= c.x && c.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= c.y &&
         c.y <= std::max(a.y, b.y);
}

bool opposite(double d1, double d2) {
  return (d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0);
}

// Closed segments p1p2 and p3p4 share at least one point.
bool segments_touch(Point p1, Point p2, Point p3, Point p4) {
  const double d1 = orient(p3, p4, p1), d2 = orient(p3, p4, p2);
  const double d3 = orient(p1, p2, p3), d4 = orient(p1, p2, p4);
  if (opposite(d1, d2) && opposite(d3, d4)) return true;
  return (d1 == 0.0 && within(p3, p4, p1)) || (d2 == 0.0 && within(p3, p4, p2)) ||
         (d3 == 0.0 && within(p1, p2, p3)) || (d4 == 0.0 && within(p1, p2, p4));
}

bool adjacent(std::size_t i, std::size_t j, std::size_t n) {
  const std::size_t d = i > j ? i - j : j - i;
  return d == 1 || d == n - 1;
}

// Consecutive edges that run back over each other (a spike of zero width).
std::optional<std::pair<std::size_t, std::size_t>> find_fold(const Polygon& poly) {
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    const Point e1 = poly[(i + 1) % n] - poly[i], e2 = poly[(i + 2) % n] - poly[(i + 1) % n];
    if (cross(e1, e2) == 0.0 && dot(e1, e2) < 0.0) return std::pair{i, (i + 1) % n};
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::pair<std::size_t, std::size_t>> find_self_intersection(const Polygon& poly) {
  const std::size_t n = poly.size();
  if (n < 3) return std::pair<std::size_t, std::size_t>{0, 0};
  if (auto fold = find_fold(poly)) return fold;
  auto lo_x = [&](std::size_t i) { return std::min(poly[i].x, poly[(i + 1) % n].x); };
  auto hi_x = [&](std::size_t i) { return std::max(poly[i].x, poly[(i + 1) % n].x); };
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return lo_x(a) < lo_x(b); });
  std::vector<std::size_t> active;
  for (const std::size_t i : order) {
    const double x0 = lo_x(i);
    std::erase_if(active, [&](std::size_t j) { return hi_x(j) < x0; });
    const Point a = poly[i], b = poly[(i + 1) % n];
    for (const std::size_t j : active) {
      if (adjacent(i, j, n)) continue;
      const Point c = poly[j], d = poly[(j + 1) % n];
      if (std::max(a.y, b.y) < std::min(c.y, d.y) || std::max(c.y, d.y) < std::min(a.y, b.y))
        continue;
      if (segments_touch(a, b, c, d)) return std::pair{std::min(i, j), std::max(i, j)};
    }
    active.push_back(i);
  }
  return std::nullopt;
}

}  // namespace gearsph::geometry
