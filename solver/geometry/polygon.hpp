#pragma once
// Points and simple polygons in the plane: the outlines the geometry module
// produces and the particle fill consumes. A Polygon is a closed ring stored
// without repeating its first vertex; bodies are counter-clockwise (CCW).
//
// Inside test and boundary rule (used by is_inside, InsideTest and
// fill_lattice alike, so they always agree): a point p is inside when the
// horizontal ray from p towards +x crosses the ring an odd number of times,
// counting an edge when lo.y <= p.y < hi.y (half-open in y) and its crossing
// abscissa is strictly greater than p.x. This is the strict interior test of
// p shifted by an infinitesimal (eps, eta), 0 < eta << eps: a point on an edge
// belongs to the polygon on its +x side, a point on a horizontal edge to the
// polygon above. Two polygons that share an edge (same two vertices, either
// direction) therefore never both claim a point on it; the crossing abscissa
// is computed from the edge ordered bottom to top, so both polygons get the
// same floating-point value.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace gearsph::geometry {

struct Point {
  double x = 0.0;
  double y = 0.0;
};

inline Point operator+(Point a, Point b) {
  return {a.x + b.x, a.y + b.y};
}
inline Point operator-(Point a, Point b) {
  return {a.x - b.x, a.y - b.y};
}
inline Point operator*(double s, Point a) {
  return {s * a.x, s * a.y};
}
inline double dot(Point a, Point b) {
  return a.x * b.x + a.y * b.y;
}
inline double cross(Point a, Point b) {
  return a.x * b.y - a.y * b.x;
}
double norm(Point a);
// a rotated counter-clockwise by `angle` about the origin.
Point rotate(Point a, double angle);

using Polygon = std::vector<Point>;

// A rigid motion: rotate by `angle` (CCW) about the origin, then translate.
struct Transform {
  double angle = 0.0;
  Point shift;
  Point apply(Point p) const { return rotate(p, angle) + shift; }
};
Polygon transformed(const Polygon& poly, const Transform& t);

struct Box {
  Point lo, hi;
};
Box bounding_box(const std::vector<Point>& points);

// Shoelace formula; positive for a CCW ring.
double signed_area(const Polygon& poly);
double perimeter(const Polygon& poly);
// Polar second moment of the enclosed area about the origin, ∫(x² + y²) dA:
// Green's theorem over each edge (positive for a CCW ring).
double polar_moment(const Polygon& poly);
// Shortest distance from p to the segments of a polyline (closed: also the
// segment from the last vertex back to the first).
double distance_to_polyline(const std::vector<Point>& line, Point p, bool closed);
// Arc length from the first vertex of a polyline to each of its vertices.
std::vector<double> cumulative_arc(const std::vector<Point>& line);
// Position at arc length s (clamped to the line) along a polyline with
// cumulative lengths `cum` (cumulative_arc).
Point at_arc(const std::vector<Point>& line, const std::vector<double>& cum, double s);

// The ray-crossing predicate shared by all inside tests (see the header
// comment). Returns true and the crossing abscissa when edge (a, b) is counted
// at height y.
bool edge_crossing(Point a, Point b, double y, double& x_cross);

// O(n) inside test with a bounding-box shortcut.
bool is_inside(const Polygon& poly, Point p);

// The same predicate with a precomputed edge table (horizontal bands, each
// listing the edges that overlap it), for millions of queries on one polygon.
class InsideTest {
 public:
  explicit InsideTest(const Polygon& poly);
  bool operator()(Point p) const;
  // Crossing abscissae of the counted edges at height y, unsorted.
  void crossings(double y, std::vector<double>& out) const;
  const Box& box() const { return box_; }

 private:
  struct Edge {
    Point lo, hi;  // lo.y < hi.y
  };
  std::size_t band_of(double y) const;
  Box box_;
  double band_height_ = 1.0;
  std::vector<Edge> edges_;
  std::vector<std::size_t> band_start_;  // CSR offsets into band_edges_
  std::vector<std::uint32_t> band_edges_;
};

// The first pair of non-adjacent edges (i, j) that touch or cross, or
// adjacent edges that fold back onto each other; nullopt for a simple ring.
// Sweep and prune on the edges' x-intervals: about O(n log n) for outlines.
std::optional<std::pair<std::size_t, std::size_t>> find_self_intersection(const Polygon& poly);

// Smallest distance between consecutive vertices (closing edge included);
// zero means a repeated vertex.
double shortest_edge(const Polygon& poly);

}  // namespace gearsph::geometry
