#pragma once
// A body's cross-section: an outer ring and any holes, each a closed
// polygon (polygon.hpp). The outer ring runs counter-clockwise and holes run
// clockwise, so that the signed areas add up to the enclosed area.
#include <vector>

#include "solver/geometry/polygon.hpp"

namespace gearsph::geometry {

struct Region {
  Polygon outer;
  std::vector<Polygon> holes;

  // Every ring, the outer one first.
  std::vector<const Polygon*> rings() const;
  double area() const;
  // The polygon.hpp inside rule on the outer ring, and outside every hole.
  bool contains(Point p) const;
};

// A circle as a counter-clockwise polygon whose chords stay within
// `chord_tolerance` of it (curve_sampling.hpp).
Polygon circle(Point centre, double radius, double chord_tolerance);

// A region from rings of either orientation: the outer one turned to
// counter-clockwise, holes to clockwise.
Region make_region(Polygon outer, std::vector<Polygon> holes = {});

}  // namespace gearsph::geometry
