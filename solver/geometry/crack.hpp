#pragma once
// A crack: a polyline in a body's reference configuration across which the
// particles do not interact (physics/crack_cut.hpp). The visibility
// criterion of meshfree methods (Belytschko, Lu & Gu 1994; Belytschko,
// Krongauz, Fleming, Organ & Liu 1996): two points see each other unless
// the segment between them crosses the crack, so each face is a free
// surface to the kernel sums, the gradient correction and the stress
// recovery. A crack grows by appending points to its tip end.
#include <vector>

#include "solver/geometry/polygon.hpp"

namespace gearsph::geometry {

struct Crack {
  int body = 0;
  // From the mouth (an edge crack's point on the free surface) or the
  // first tip to the tip; at least two points.
  std::vector<Point> path;
  bool front_is_tip = false;  // a crack inside the body (both ends are tips)
};

// The segment a-b crosses the crack: a and b lie strictly on opposite sides
// of one of its segments, and the crossing point lies on that segment, short
// of a tip (a pair that passes exactly through a tip still sees across it).
bool crack_cuts(const Crack& crack, Point a, Point b);
// The same, with the index of the first segment it crosses (path[k] to
// path[k + 1]), or -1.
int crack_segment_cut(const Crack& crack, Point a, Point b);
bool any_crack_cuts(const std::vector<Crack>& cracks, Point a, Point b);

}  // namespace gearsph::geometry
