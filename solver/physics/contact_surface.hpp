#pragma once
// Surface contact: the seed paper's linear penalty law, applied to the gap
// between the bodies' true surfaces instead of the distance between particle
// centres.
//
// Why: on a square lattice the outermost particles of an inclined flank sit
// anywhere from 0 to about 0.7 dx below the surface. With the seed paper's
// criterion (centres closer than r0 = dx) two flanks sliding past each other
// feel a washboard of bumps of that height, and a clearance smaller than dx
// (gear backlash is 0.1 mm at dx = 1 mm) does not exist at all: the rack is
// wedged between the teeth and the contact forces grow without bound.
//
// Each particle near a surface knows its depth below it and the outward
// normal there (scene/surfaces.hpp), turned with the material's rotation. A
// pair (i of body A, j of body B) with facing normals defines
//   n = normalize(n_j - n_i)                  (from j towards i)
//   g = max over the two tangent lines of the surface points' separation
//       (= (x_i - x_j) . n - depth_i - depth_j for facing flat surfaces)
//   s = |(x_i - x_j) x n|                     the lateral offset
// and, for g < 0 and s < dx,
//   F_ij = k (-g) (1 - s/dx) n,  k = D E* V_ij / dx^2.
// The hat weight 1 - s/dx of the lateral offset sums to one over a row of
// partners spaced dx along a flat surface, whatever their alignment, so a
// particle sliding along a flank feels a constant force. Every quantity is
// symmetric in (i, j) except n, which flips: F_ji = -F_ij.
#include <algorithm>
#include <cmath>

#include "solver/physics/contact_seed_penalty.hpp"

namespace gearsph::physics {

struct SurfacePair {
  bool active = false;
  double nx = 0.0, ny = 0.0;  // unit normal from j to i
  double overlap = 0.0;       // -g > 0
  double weight = 0.0;        // 1 - s/dx
};

// d = x_i - x_j; (nix, niy), (njx, njy): current outward normals.
inline SurfacePair surface_pair(double dx_ij, double dy_ij, double nix, double niy, double njx,
                                double njy, double depth_i, double depth_j, double dx) {
  SurfacePair s;
  // Surface points carried by the particles, s = x + depth n, and the gap of
  // each from the other's tangent line; the pair is separated if either
  // tangent line separates them (so a corner passing a flank side-on is not
  // taken for a contact). For facing flat surfaces both equal
  // d . n - depth_i - depth_j. Tested first: most candidates are apart, and
  // the gap needs neither square root nor division.
  const double sx = dx_ij + depth_i * nix - depth_j * njx;  // s_i - s_j
  const double sy = dy_ij + depth_i * niy - depth_j * njy;
  const double gap_i = -(sx * nix + sy * niy);  // s_j beyond i's tangent line
  const double gap_j = sx * njx + sy * njy;     // s_i beyond j's tangent line
  const double g = std::max(gap_i, gap_j);
  if (g >= 0.0) return s;
  double nx = njx - nix, ny = njy - niy;
  const double len = std::sqrt(nx * nx + ny * ny);
  // Normals that do not face each other (|n_j - n_i| < sqrt(2): more than 90
  // degrees from opposed) are two surfaces side by side, not in contact.
  if (!(len > 1.41)) return s;
  nx /= len;
  ny /= len;
  const double lateral = std::abs(dx_ij * ny - dy_ij * nx);
  if (lateral >= dx) return s;
  s.active = true;
  s.nx = nx;
  s.ny = ny;
  s.overlap = -g;
  s.weight = 1.0 - lateral / dx;
  return s;
}

}  // namespace gearsph::physics
