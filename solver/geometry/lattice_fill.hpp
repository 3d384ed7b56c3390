#pragma once
// Particle placement inside an outline: the cell centres of a square grid of
// spacing dx anchored at `origin` (points origin + ((a + 1/2) dx, (b + 1/2) dx))
// that the polygon contains. Each point stands for one dx^2 cell, so bodies
// filled on the same grid tile the plane with no gap and no overlap; a point
// exactly on a shared edge goes to one body only (rule in polygon.hpp).
// Same grid convention as solver/scene/lattice.hpp.
#include <vector>

#include "solver/geometry/polygon.hpp"

namespace gearsph::geometry {

// The lattice point (a, b); out of line so that every caller gets the same bits.
Point lattice_point(Point origin, double dx, long a, long b);

// Lattice points inside `poly`, row by row (b, then a, ascending). Scanline:
// per row the edge crossings are sorted once, so the cost is about
// (edges + points). Exactly the points for which is_inside() is true.
std::vector<Point> fill_lattice(const Polygon& poly, double dx, Point origin);

}  // namespace gearsph::geometry
