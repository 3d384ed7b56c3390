#pragma once
// A plane region bounded by lines, circular arcs and splines through the
// points of a generated outline, meshed by gmsh into six-node triangles
// with the element size set by distance to chosen curves and points.
//
// The region is written as a .geo file (gmsh's own geometry language: a
// reviewer can open it in gmsh and see the model and its size fields), and
// gmsh runs on it as a program (external_program.hpp) writing an ASCII
// MSH 2.2 file, which read_msh22 reads back.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "fe/external_program.hpp"
#include "fe/tri_mesh.hpp"
#include "solver/geometry/polygon.hpp"

namespace gearsph::fe {

struct Curve {
  enum class Kind { Line, Arc, Spline };
  Kind kind = Kind::Spline;
  // Line: its two ends. Arc: start and end, less than half a turn apart,
  // about `centre`. Spline: passes through every point (gmsh's Catmull-Rom
  // spline), so a dense outline is followed to well within its own chord
  // error.
  std::vector<Point> points;
  Point centre;
  std::string group;  // boundary group (node sets, loads); "" for none
};

// A closed chain: each curve starts where the previous one ends (the same
// point, compared exactly), the last ends where the first starts.
using CurveLoop = std::vector<Curve>;

// Element size `size_min` within `dist_min` of the listed curves and points,
// rising linearly to `size_max` at `dist_max` (gmsh Distance and Threshold
// fields); the smallest of all zones and MeshSpec::size_max applies.
struct SizeZone {
  std::vector<std::pair<int, int>> curves;  // (loop, curve)
  std::vector<Point> points;
  double size_min = 0.0, size_max = 0.0, dist_min = 0.0, dist_max = 0.0;
};

struct MeshSpec {
  std::vector<CurveLoop> loops;  // the first is the outer boundary, the others holes
  double size_max = 0.0;         // [m], everywhere
  std::vector<SizeZone> zones;
};

// The .geo text: second-order elements with mid-side nodes on the curves,
// Frontal-Delaunay, one thread (the same input gives the same mesh).
std::string gmsh_geo(const MeshSpec& spec);

// Six-node triangles and the boundary groups' three-node lines of an ASCII
// MSH 2.2 file. Nodes are renumbered from 0 in file order, keeping only
// those of the triangles; every triangle is turned counter-clockwise.
TriMesh read_msh22(const std::string& text);

// Writes `name`.geo in `work_dir`, runs gmsh, reads `name`.msh.
TriMesh mesh_with_gmsh(const MeshSpec& spec, const FeTools& tools,
                       const std::filesystem::path& work_dir, const std::string& name,
                       double timeout_s);

// A closed polygon cut into curves at the given vertices (and at every
// corner turning more than `corner_rad`; with cut_chord_jumps also where one
// chord is more than four times as long as the next, so that a straight
// chord between sampled curves is a Line): a Line where a piece is two
// vertices, a Spline otherwise. Returns the curves in order, the i-th
// starting at the i-th cut vertex (ascending indices).
struct PolygonPieces {
  std::vector<Curve> curves;
  std::vector<std::size_t> first_vertex;  // where each curve starts
};
PolygonPieces polygon_curves(const geometry::Polygon& poly, std::vector<std::size_t> cuts,
                             double corner_rad, bool cut_chord_jumps = false);

}  // namespace gearsph::fe
