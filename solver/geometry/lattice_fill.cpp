#include "solver/geometry/lattice_fill.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gearsph::geometry {

[[gnu::noinline]] Point lattice_point(Point origin, double dx, long a, long b) {
  return {origin.x + (static_cast<double>(a) + 0.5) * dx,
          origin.y + (static_cast<double>(b) + 0.5) * dx};
}

namespace {
// Index range of lattice coordinates whose cell centres may fall in [lo, hi]
// (one extra on each side; the inside test decides).
std::pair<long, long> index_range(double lo, double hi, double o, double dx) {
  return {static_cast<long>(std::floor((lo - o) / dx - 0.5)) - 1,
          static_cast<long>(std::ceil((hi - o) / dx - 0.5)) + 1};
}
}  // namespace

std::vector<Point> fill_lattice(const Polygon& poly, double dx, Point origin) {
  if (!(dx > 0.0)) throw std::invalid_argument("fill_lattice: spacing dx must be positive");
  std::vector<Point> points;
  if (poly.size() < 3) return points;
  const InsideTest inside(poly);
  const Box box = inside.box();
  const auto [a0, a1] = index_range(box.lo.x, box.hi.x, origin.x, dx);
  const auto [b0, b1] = index_range(box.lo.y, box.hi.y, origin.y, dx);
  std::vector<double> xs;
  for (long b = b0; b <= b1; ++b) {
    const double y = lattice_point(origin, dx, 0, b).y;
    inside.crossings(y, xs);
    if (xs.empty()) continue;
    std::sort(xs.begin(), xs.end());
    for (long a = a0; a <= a1; ++a) {
      const Point p = lattice_point(origin, dx, a, b);
      if (p.x < box.lo.x || p.x > box.hi.x) continue;
      // Odd number of crossings strictly to the right: inside (polygon.hpp).
      const auto right = xs.end() - std::upper_bound(xs.begin(), xs.end(), p.x);
      if (right % 2 == 1) points.push_back(p);
    }
  }
  return points;
}

}  // namespace gearsph::geometry
