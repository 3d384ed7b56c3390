#include "solver/geometry/curve_sampling.hpp"

#include <cmath>

namespace gearsph::geometry::detail {

double distance_to_chord(Point a, Point b, Point p) {
  const Point ab = b - a;
  const double len = norm(ab);
  if (len == 0.0) return norm(p - a);
  return std::abs(cross(ab, p - a)) / len;
}

}  // namespace gearsph::geometry::detail
