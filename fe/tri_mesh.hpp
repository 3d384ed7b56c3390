#pragma once
// A mesh of six-node (quadratic) triangles in the plane, as gmsh writes it
// and CalculiX reads it, and what the rest of the FE layer needs of its
// boundary: the edges that belong to one element only, traction loads
// spread over them, and nodal values read back at points on them.
#include <array>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "solver/geometry/polygon.hpp"

namespace gearsph::fe {

using geometry::Point;

struct TriMesh {
  std::vector<Point> nodes;  // [m]
  // Corners counter-clockwise, then the mid-side nodes of the edges 1-2,
  // 2-3, 3-1 (0-based node indices): the order of gmsh's 9-node type and of
  // CalculiX's CPE6.
  std::vector<std::array<int, 6>> elements;
  // Boundary curves by group name: each edge as {end, end, middle}.
  std::map<std::string, std::vector<std::array<int, 3>>> groups;
};

// Nodes of a group's edges, each once, ascending.
std::vector<int> group_nodes(const TriMesh& mesh, const std::string& group);

// An element edge on the boundary, in the element's counter-clockwise order:
// the body lies on its left, the outward normal points to its right.
struct BoundaryEdge {
  int a = 0, mid = 0, b = 0;
  int element = 0;
};
std::vector<BoundaryEdge> boundary_edges(const TriMesh& mesh);
// The boundary edges of a group, oriented as above; throws if the group
// has an edge that is not on the boundary.
std::vector<BoundaryEdge> group_edges(const TriMesh& mesh,
                                      const std::vector<BoundaryEdge>& boundary,
                                      const std::string& group);

// Position and tangent dx/dxi on a quadratic edge, xi in [0, 1] (a at 0,
// mid at 1/2, b at 1).
Point edge_point(const TriMesh& mesh, const BoundaryEdge& e, double xi);
Point edge_tangent(const TriMesh& mesh, const BoundaryEdge& e, double xi);

// Consistent nodal forces of a traction (force per area, a function of the
// position and the outward unit normal) over `edges`, per unit thickness:
// f_i = integral of N_i t ds, by Gauss-Legendre on `pieces` equal parts of
// each edge, so that a traction that starts or ends inside an edge (a
// contact patch) is integrated accurately. One force per mesh node.
using Traction = std::function<Point(Point x, Point outward_normal)>;
std::vector<Point> traction_forces(const TriMesh& mesh, const std::vector<BoundaryEdge>& edges,
                                   const Traction& traction, int pieces = 8);

// Where a point lies on the boundary: the nearest of `edges` (distance to
// the edge's curve) and the edge parameter there.
struct EdgeHit {
  std::size_t edge = 0;
  double xi = 0.0;
  double distance = 0.0;
};
EdgeHit nearest_edge(const TriMesh& mesh, const std::vector<BoundaryEdge>& edges, Point p);

// A nodal value read at an edge parameter by the edge's quadratic shape
// functions.
double along_edge(const BoundaryEdge& e, double xi, const std::vector<double>& nodal);

}  // namespace gearsph::fe
