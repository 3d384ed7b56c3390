#include "solver/geometry/crack.hpp"

#include <algorithm>

namespace gearsph::geometry {

namespace {

// Crossings this close to a tip (as a fraction of the segment) count as
// through the tip: on a lattice whose rows straddle a tip, a pair and its
// mirror image cross exactly there, and round-off must not cut one and
// keep the other (that breaks the symmetry of a mode-I crack, K_II != 0).
constexpr double kAtTip = 1e-9;

// Twice the signed area of (a, b, c): > 0 when c is left of a -> b.
double orientation(Point a, Point b, Point c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// a-b crosses c-d at c + t (d - c) with a, b strictly on opposite sides of
// the line c-d, and short of d (a tip, or a joint that the next segment
// covers from its own start); past c too when c is a tip.
bool crosses(Point a, Point b, Point c, Point d, bool open_start) {
  const double sa = orientation(c, d, a), sb = orientation(c, d, b);
  if (!((sa > 0.0 && sb < 0.0) || (sa < 0.0 && sb > 0.0))) return false;
  const double sc = orientation(a, b, c), sd = orientation(a, b, d);
  if (sc == sd) return false;  // parallel (cannot be with sa, sb of opposite sign)
  const double t = sc / (sc - sd);
  return (open_start ? t > kAtTip : t >= -kAtTip) && t < 1.0 - kAtTip;
}

}  // namespace

bool crack_cuts(const Crack& crack, Point a, Point b) {
  return crack_segment_cut(crack, a, b) >= 0;
}

int crack_segment_cut(const Crack& crack, Point a, Point b) {
  const std::vector<Point>& p = crack.path;
  for (std::size_t k = 0; k + 1 < p.size(); ++k) {
    // A quick reject on the bounding boxes: most pairs are far from the crack.
    if (std::max(a.x, b.x) < std::min(p[k].x, p[k + 1].x) ||
        std::min(a.x, b.x) > std::max(p[k].x, p[k + 1].x) ||
        std::max(a.y, b.y) < std::min(p[k].y, p[k + 1].y) ||
        std::min(a.y, b.y) > std::max(p[k].y, p[k + 1].y)) {
      continue;
    }
    if (crosses(a, b, p[k], p[k + 1], k == 0 && crack.front_is_tip)) return static_cast<int>(k);
  }
  return -1;
}

bool any_crack_cuts(const std::vector<Crack>& cracks, Point a, Point b) {
  return std::any_of(cracks.begin(), cracks.end(),
                     [&](const Crack& c) { return crack_cuts(c, a, b); });
}

}  // namespace gearsph::geometry
