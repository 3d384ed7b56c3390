#pragma once
// A particle field as a continuous field inside its bodies, for drawing as
// contours (mesh_image.hpp) rather than as discs.
//
//  - The particles are joined by their Delaunay triangulation, the dual of
//    their Voronoi diagram (Boost.Polygon's, exact on integer input), and a
//    triangle is kept where its three particles belong to one body and its
//    centroid lies inside that body's outlines (even-odd, so a bore is a
//    hole; or outside by a sliver, the outline row's chord of a fillet): no triangle bridges a
//    tooth space or two bodies in contact.
//  - The drawn field is smoothed by Taubin's filter, whose Laplacian is the
//    residual of a particle's value from the plane through its
//    neighbours': a linear field, and so the gradient a fillet's peak sits
//    on, is kept exactly, the particle-to-particle zig-zag of SPH's nodal
//    integration (hourglass modes, docs/stability.md) is damped, and a
//    smooth peak keeps its height (no shrinkage). The drawing alone is
//    smoothed: every number a run reports is read by its own recovery
//    (diagnostics/stress_recovery.hpp, edge_stress.hpp).
//  - The zig-zag indicator of a drawn field is the health monitor's
//    (diagnostics/health.hpp) on the triangulation's edges: the part of the
//    field that differs from its neighbours, over the field's RMS (a
//    checkerboard gives 1 or more, a smooth field nearly 0). On a lattice
//    the health monitor compares with the neighbours' mean; on graded,
//    irregular particles that mean sits off the particle, and a steep but
//    linear field (a fillet's) would read as zig-zag, so the neighbours'
//    least-squares plane at the particle stands for their mean here (the
//    same on a lattice's symmetric neighbourhood).
#include <array>
#include <vector>

#include "render/field_image.hpp"

namespace gearsph::render {

struct ParticleMesh {
  std::vector<std::array<int, 3>> triangles;  // particle indices, counter-clockwise
  std::vector<std::vector<int>> neighbours;   // each particle's, along the kept triangles' edges
};

// Triangulated at `x`, `y` (the reference configuration, with the outlines
// as stored, so that a deformed or turned body keeps its triangles; draw
// them at the current positions). `outline_body[k]`: the body of
// `outlines[k]` (-1: none). A body without
// an outline keeps every triangle of its own particles whose edges are at
// most `max_edge_m` long (0: no limit).
ParticleMesh particle_mesh(const std::vector<double>& x, const std::vector<double>& y,
                           const std::vector<int>& body, const std::vector<Polyline>& outlines,
                           const std::vector<int>& outline_body, double max_edge_m = 0.0);

// The field to draw (above); a particle with fewer than three neighbours
// keeps its value. NaN stays NaN.
std::vector<double> smoothed_for_drawing(const std::vector<double>& x, const std::vector<double>& y,
                                         const std::vector<double>& value,
                                         const ParticleMesh& mesh);

// sqrt(sum (v_i - P_i(x_i))^2 / sum v_i^2), P_i the plane fitted through
// the values of i's neighbours, over the particles with three neighbours
// or more (and `only`, when given, those whose flag is set).
double zigzag_indicator(const std::vector<double>& x, const std::vector<double>& y,
                        const std::vector<double>& value, const ParticleMesh& mesh,
                        const std::vector<unsigned char>* only = nullptr);

}  // namespace gearsph::render
