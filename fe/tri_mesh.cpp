#include "fe/tri_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <stdexcept>
#include <unordered_map>

namespace gearsph::fe {

namespace {

std::uint64_t edge_key(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (hi << 32) | lo;
}

// Quadratic shape functions on [0, 1] and their derivatives (a, mid, b).
std::array<double, 3> shape(double xi) {
  return {(1.0 - xi) * (1.0 - 2.0 * xi), 4.0 * xi * (1.0 - xi), xi * (2.0 * xi - 1.0)};
}
std::array<double, 3> shape_slope(double xi) {
  return {4.0 * xi - 3.0, 4.0 - 8.0 * xi, 4.0 * xi - 1.0};
}

// Four-point Gauss-Legendre on [-1, 1] (Abramowitz & Stegun 25.4.30).
constexpr double kGaussX[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                               0.8611363115940526};
constexpr double kGaussW[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                               0.3478548451374538};

}  // namespace

std::vector<int> group_nodes(const TriMesh& mesh, const std::string& group) {
  std::set<int> nodes;
  const auto it = mesh.groups.find(group);
  if (it == mesh.groups.end()) throw std::invalid_argument("mesh has no boundary group " + group);
  for (const auto& e : it->second) nodes.insert(e.begin(), e.end());
  return {nodes.begin(), nodes.end()};
}

std::vector<BoundaryEdge> boundary_edges(const TriMesh& mesh) {
  std::unordered_map<std::uint64_t, int> count;
  count.reserve(3 * mesh.elements.size());
  for (const auto& el : mesh.elements) {
    for (int k = 0; k < 3; ++k) ++count[edge_key(el[k], el[(k + 1) % 3])];
  }
  std::vector<BoundaryEdge> out;
  for (std::size_t i = 0; i < mesh.elements.size(); ++i) {
    const auto& el = mesh.elements[i];
    for (int k = 0; k < 3; ++k) {
      const int a = el[k], b = el[(k + 1) % 3];
      if (count[edge_key(a, b)] == 1) out.push_back({a, el[3 + k], b, static_cast<int>(i)});
    }
  }
  return out;
}

std::vector<BoundaryEdge> group_edges(const TriMesh& mesh,
                                      const std::vector<BoundaryEdge>& boundary,
                                      const std::string& group) {
  std::unordered_map<std::uint64_t, std::size_t> where;
  for (std::size_t i = 0; i < boundary.size(); ++i)
    where[edge_key(boundary[i].a, boundary[i].b)] = i;
  const auto it = mesh.groups.find(group);
  if (it == mesh.groups.end()) throw std::invalid_argument("mesh has no boundary group " + group);
  std::vector<BoundaryEdge> out;
  for (const auto& e : it->second) {
    const auto w = where.find(edge_key(e[0], e[1]));
    if (w == where.end()) throw std::runtime_error("group " + group + " has an interior edge");
    out.push_back(boundary[w->second]);
  }
  return out;
}

Point edge_point(const TriMesh& mesh, const BoundaryEdge& e, double xi) {
  const auto n = shape(xi);
  return n[0] * mesh.nodes[e.a] + n[1] * mesh.nodes[e.mid] + n[2] * mesh.nodes[e.b];
}

Point edge_tangent(const TriMesh& mesh, const BoundaryEdge& e, double xi) {
  const auto d = shape_slope(xi);
  return d[0] * mesh.nodes[e.a] + d[1] * mesh.nodes[e.mid] + d[2] * mesh.nodes[e.b];
}

std::vector<Point> traction_forces(const TriMesh& mesh, const std::vector<BoundaryEdge>& edges,
                                   const Traction& traction, int pieces) {
  std::vector<Point> f(mesh.nodes.size());
  const double part = 1.0 / std::max(1, pieces);
  for (const BoundaryEdge& e : edges) {
    for (int k = 0; k < pieces; ++k) {
      for (int g = 0; g < 4; ++g) {
        const double xi = part * (k + 0.5 * (kGaussX[g] + 1.0));
        const Point t = edge_tangent(mesh, e, xi);
        const double ds = geometry::norm(t);
        if (ds == 0.0) continue;
        const Point normal{t.y / ds, -t.x / ds};  // right of the edge: outward
        const Point q = traction(edge_point(mesh, e, xi), normal);
        const double w = 0.5 * part * kGaussW[g] * ds;
        const auto n = shape(xi);
        f[e.a] = f[e.a] + (w * n[0]) * q;
        f[e.mid] = f[e.mid] + (w * n[1]) * q;
        f[e.b] = f[e.b] + (w * n[2]) * q;
      }
    }
  }
  return f;
}

EdgeHit nearest_edge(const TriMesh& mesh, const std::vector<BoundaryEdge>& edges, Point p) {
  if (edges.empty()) throw std::invalid_argument("nearest_edge: no edges");
  EdgeHit best;
  best.distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const BoundaryEdge& e = edges[i];
    const Point a = mesh.nodes[e.a], b = mesh.nodes[e.b], m = mesh.nodes[e.mid];
    // The curve stays within the bow of its middle node from the chord.
    const double bow = geometry::norm(m - 0.5 * (a + b));
    const double chord = geometry::distance_to_polyline({a, b}, p, false);
    if (chord - 2.0 * bow > best.distance) continue;
    // Coarse scan, then golden-section search around the best sample.
    constexpr int kScan = 16;
    double xi_best = 0.0, d_best = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= kScan; ++k) {
      const double xi = static_cast<double>(k) / kScan;
      const double d = geometry::norm(edge_point(mesh, e, xi) - p);
      if (d < d_best) d_best = d, xi_best = xi;
    }
    double lo = std::max(0.0, xi_best - 1.0 / kScan), hi = std::min(1.0, xi_best + 1.0 / kScan);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int it = 0; it < 40; ++it) {
      const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
      if (geometry::norm(edge_point(mesh, e, x1) - p) < geometry::norm(edge_point(mesh, e, x2) - p))
        hi = x2;
      else
        lo = x1;
    }
    const double xi = 0.5 * (lo + hi);
    const double d = geometry::norm(edge_point(mesh, e, xi) - p);
    if (d < best.distance) best = {i, xi, d};
  }
  return best;
}

double along_edge(const BoundaryEdge& e, double xi, const std::vector<double>& nodal) {
  const auto n = shape(xi);
  return n[0] * nodal[e.a] + n[1] * nodal[e.mid] + n[2] * nodal[e.b];
}

}  // namespace gearsph::fe
