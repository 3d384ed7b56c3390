#pragma once
// Body-fitted particles: a row on the true outline at an even arc-length
// spacing, and an interior relaxed to the (graded) spacing s(x) of a
// SpacingField, each particle with the area of its Voronoi cell clipped to
// the body as its volume. No staircase: the outline the particles stand for
// is the outline of the part.
//
// 1. Outline: each ring is cut at its corners (a turn sharper than
//    `corner_angle_deg` at one vertex), and each piece between corners is
//    sampled at equal steps of the stretched arc length  tau = int dl / s,
//    a whole number of steps per piece, so corners carry a particle.
// 2. Interior, first guess: the leaves of a quadtree split until a leaf is
//    no larger than s, one point per s^2 of leaf area by error diffusion
//    along the tree (deterministic), none within half a spacing of the
//    outline (the outline row stands for that band).
// 3. Relaxation: Lloyd's iteration towards a centroidal Voronoi
//    tessellation with density s^-4 (cell size ~ density^(-1/4) in 2D; Du,
//    Faber & Gunzburger 1999), the outline row held: each interior point
//    moves to the density-weighted centroid of its clipped cell, until the
//    largest move is below `tolerance` spacings. The interior settles into
//    a nearly hexagonal packing graded with s, and the first row inside
//    sits about a spacing from the outline. This is the role SPHinXsys'
//    level-set relaxation and PySPH's packing play (Negi & Ramachandran
//    2021, CPC 279); Lloyd's centroids need no force law or time step and
//    give the volumes on the way.
// 4. Volumes: the clipped Voronoi areas, which add up to the region's area.
//
// Everything is deterministic: the same region and field give the same
// particles, bit for bit, on any thread count.
#include <cstdint>
#include <vector>

#include "solver/geometry/region.hpp"
#include "solver/geometry/spacing_field.hpp"

namespace gearsph::geometry {

struct BodyFittedOptions {
  int max_iterations = 80;
  double tolerance = 0.01;       // largest move, in local spacings, that ends the relaxation
  double corner_angle_deg = 25;  // a sharper turn at one vertex is a corner
};

struct BodyFittedParticles {
  std::vector<Point> points;
  std::vector<double> volume;         // clipped Voronoi area [m^2 per m]
  std::vector<double> spacing;        // s at the particle [m]
  std::vector<std::uint8_t> outline;  // 1: on the outline (held during relaxation)
  int iterations = 0;                 // Lloyd iterations taken
  double last_move = 0.0;             // largest move of the last one, in local spacings
};

BodyFittedParticles fill_body_fitted(const Region& region, const SpacingField& spacing,
                                     const BodyFittedOptions& options = {});

// The outline rows alone (step 1), ring by ring: for tests and drawings.
std::vector<Point> sample_outline(const Polygon& ring, const SpacingField& spacing,
                                  double corner_angle_deg);

}  // namespace gearsph::geometry
