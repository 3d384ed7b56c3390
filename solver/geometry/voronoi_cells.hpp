#pragma once
// The Voronoi cell of each point, clipped to a region: its area (a
// particle's volume, per unit thickness) and its centroid, optionally
// weighted by a density (Lloyd's relaxation towards a centroidal Voronoi
// tessellation; Du, Faber & Gunzburger 1999, SIAM Review 41).
//
// The cells partition the plane, so the clipped areas add up to the
// region's area to round-off, whatever the points. The diagram comes from
// Boost.Polygon (exact predicates on integer input: the points are snapped
// to a grid 2^-29 of the region's extent), the clipping from
// Boost.Geometry. Only cells that reach the outline are clipped, each
// against the region cut into tiles, so a clip touches a few dozen outline
// segments instead of thousands.
#include <functional>
#include <memory>
#include <vector>

#include "solver/geometry/region.hpp"

namespace gearsph::geometry {

class ClippedVoronoi {
 public:
  // `tile` is the side of the tiles the region is cut into: a few times the
  // largest cell.
  ClippedVoronoi(const Region& region, double tile);
  ~ClippedVoronoi();

  struct Cell {
    double area = 0.0;
    Point centroid;  // weighted by the density when one is given
  };
  // One cell per point, in order. Points must be distinct (after snapping)
  // and inside the region. `density` (may be empty) weights the centroid.
  std::vector<Cell> cells(const std::vector<Point>& points,
                          const std::function<double(Point)>& density = {}) const;

  // Distance from p to the region's outline.
  double distance_to_outline(Point p) const;
  bool contains(Point p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gearsph::geometry
