#include "solver/geometry/region.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "solver/geometry/curve_sampling.hpp"

namespace gearsph::geometry {

std::vector<const Polygon*> Region::rings() const {
  std::vector<const Polygon*> out{&outer};
  for (const Polygon& h : holes) out.push_back(&h);
  return out;
}

double Region::area() const {
  double a = signed_area(outer);
  for (const Polygon& h : holes) a += signed_area(h);
  return a;
}

bool Region::contains(Point p) const {
  if (!is_inside(outer, p)) return false;
  return std::none_of(holes.begin(), holes.end(),
                      [p](const Polygon& h) { return is_inside(h, p); });
}

Polygon circle(Point centre, double radius, double chord_tolerance) {
  Polygon out;
  sample_curve(
      [&](double a) {
        return Point{centre.x + radius * std::cos(a), centre.y + radius * std::sin(a)};
      },
      0.0, 2.0 * std::numbers::pi, chord_tolerance, out);
  return out;
}

Region make_region(Polygon outer, std::vector<Polygon> holes) {
  if (signed_area(outer) < 0.0) std::reverse(outer.begin(), outer.end());
  for (Polygon& h : holes) {
    if (signed_area(h) > 0.0) std::reverse(h.begin(), h.end());
  }
  return {std::move(outer), std::move(holes)};
}

}  // namespace gearsph::geometry
