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
  // -d(overlap)/d(x_i - x_j): the force's direction on i, from j (a unit
  // normal, or nearly: the common normal at the contact point unnormalised)
  double nx = 0.0, ny = 0.0;
  double overlap = 0.0;  // -g > 0
  double weight = 0.0;   // 1 - s/dx (curved: the two hats)
  // The weight's gradient in x_i - x_j, dweight (tx, ty): the force on i is
  // F w n - Phi dweight t, the gradient of the pair's energy w Phi(overlap).
  double tx = 0.0, ty = 0.0, dweight = 0.0;
};

// d = x_i - x_j; (nix, niy), (njx, njy): current outward normals.
//
// on_outline: both particles sit on their outlines (body-fitted, depth 0),
// and the pair starts where they come within dx of each other
// (contact.cpp). Its weight is then the hat of their distance, 1 - |d|/dx,
// not of the lateral offset: it vanishes where the pair starts. A corner's
// tangent line, extended, can already cross the other surface at that
// distance; with the lateral hat the pair switched on with a gap of -28 um
// and a weight of 0.08, and energy appeared in one step (docs/contact.md,
// "A corner's pair starts with no weight"). Along a flat row of partners the two hats differ by the
// overlap squared over dx, a micron's worth.
//
// kappa_i, kappa_j (on_outline only): the curvature of a particle whose
// surface is a parabola (away from corners; 0 for a corner or a particle
// beside one), so that the other's surface point is measured from that
// parabola, not from its tangent line. A pinion flank particle low on the
// flank (radius of curvature 2-3 mm) has its tangent line 0.2 mm outside
// its surface a millimetre away, where a rack tip corner of 1 mm spacing
// passes in the backlash: measured from the line, the corner overlapped
// by up to 30 um and the unloaded mesh rang with 1.2 kN contact forces.
//
// corner_i, corner_j (on_outline only): the particle draws a convex corner
// (its outline turns by kCornerTurning or more over its spacing). A corner
// has no tangent line: pressed on a smooth surface it is a point on a face,
// whose gap and normal are the face's (the node-to-segment contact of the
// finite-element codes; Wriggers, Computational Contact Mechanics, 2006,
// 4.1), so only the other particle's line measures the pair. Measured from
// the larger of the two gaps, the paper's pinion loaded at its tip corner
// switched from the corner's line to the flank's at 4.5 kN of 7; the
// corner's line turns with the corner's receivers, and the energy's
// derivative in that turn (contact_pairs.cpp) loaded the tooth with a
// couple that came and went with the switch: the fillet peak per kilonewton
// rose by 5.6 % between half the load and all of it (docs/gears.md).
inline SurfacePair surface_pair(double dx_ij, double dy_ij, double nix, double niy, double njx,
                                double njy, double depth_i, double depth_j, double dx,
                                bool on_outline = false, double kappa_i = 0.0, double kappa_j = 0.0,
                                bool corner_i = false, bool corner_j = false) {
  SurfacePair s;
  // Surface points carried by the particles, s = x + depth n, and the gap of
  // each from the other's tangent line; the pair is separated if either
  // tangent line separates them (so a corner passing a flank side-on is not
  // taken for a contact). For facing flat surfaces both equal
  // d . n - depth_i - depth_j. Tested first: most candidates are apart, and
  // the gap needs neither square root nor division.
  const double sx = dx_ij + depth_i * nix - depth_j * njx;  // s_i - s_j
  const double sy = dy_ij + depth_i * niy - depth_j * njy;
  // s_j beyond i's surface and s_i beyond j's: their tangent lines, less
  // each parabola's sag kappa t^2 / 2 at the other's offset t along it.
  const double ti = sx * niy - sy * nix, tj = sx * njy - sy * njx;
  const double gap_i = -(sx * nix + sy * niy) + 0.5 * kappa_i * ti * ti;
  const double gap_j = sx * njx + sy * njy + 0.5 * kappa_j * tj * tj;
  // Whose line measures the pair: a corner's partner's, else the larger gap.
  const bool from_i = corner_i != corner_j ? corner_j : gap_i >= gap_j;
  const double g = from_i ? gap_i : gap_j;
  if (g >= 0.0) return s;
  double nx = njx - nix, ny = njy - niy;
  const double len = std::sqrt(nx * nx + ny * ny);
  // Normals that do not face each other (|n_j - n_i| < sqrt(2): more than 90
  // degrees from opposed) are two surfaces side by side, not in contact.
  if (!(len > 1.41)) return s;
  nx /= len;
  ny /= len;
  const double cross = dx_ij * ny - dy_ij * nx;
  const double lateral = std::abs(cross);
  if (lateral >= dx) return s;
  s.active = true;
  // The overlap's gradient: that of the gap that decides it, the normal of
  // its tangent line tilted by the parabola's slope at the offset.
  if (from_i) {
    s.nx = -nix + kappa_i * ti * niy;
    s.ny = -niy - kappa_i * ti * nix;
  } else {
    s.nx = njx + kappa_j * tj * njy;
    s.ny = njy - kappa_j * tj * njx;
  }
  s.overlap = -g;
  if (on_outline) {
    const double r = std::sqrt(dx_ij * dx_ij + dy_ij * dy_ij);
    if (!(r < dx)) return SurfacePair{};
    s.weight = 1.0 - r / dx;
    // d(weight)/d(x_i - x_j) = -(1 / dx) d / |d|.
    s.tx = r > 0.0 ? dx_ij / r : 0.0;
    s.ty = r > 0.0 ? dy_ij / r : 0.0;
    s.dweight = -1.0 / dx;
    return s;
  }
  s.weight = 1.0 - lateral / dx;
  // d(weight)/d(x_i - x_j) = -(sign / dx) (n_y, -n_x).
  s.tx = ny;
  s.ty = -nx;
  s.dweight = cross > 0.0 ? -1.0 / dx : 1.0 / dx;
  return s;
}

// Two curved outline particles (body-fitted, depth 0) of a convex pair:
// the overlap of the two surfaces, not of the particles.
//
// Why: a flank's curvature moves its surface away from the other body by
// kappa t^2 / 2 at a distance t from the contact along it. The gap between
// particles, read at the particles, misses the approach by up to
// K h^2 / 8 (K = kappa_i + kappa_j) when the contact falls half a spacing h
// from both: 4 um at the pinion's pitch point and its 0.51 mm flank
// spacing, as much as the whole mesh deflection at 1 kN. The mesh stiffness
// then depended on where the contact fell between particles (docs/contact.md,
// "Where the contact falls between particles").
//
// Each particle's surface near it is its osculating parabola: in the
// pair's frame (n from j to i, tau = z x n, origin at j's surface point,
// i's at (d_t, d_n)) the surfaces' heights are
//   h_i(t) = d_n + alpha (t - d_t) + k_i (t - d_t)^2 / 2,
//   h_j(t) = -alpha t - k_j t^2 / 2,
// alpha the tilt of each normal from the bisector n (equal and opposite
// because n bisects them) and k = kappa (1 + alpha^2)^(3/2) the curvature
// of each height function. Their gap g(t) = h_i - h_j is least at
//   t* = (k_i d_t - 2 alpha) / K,
// where the surfaces would first touch: the contact point X. The overlap
// is -g(t*), the force along its gradient (the surfaces' common normal at
// X) plus the hats' own gradient, so that the pair's energy w Phi(overlap)
// is conserved as X slides along the rows; the pair's weight is the
// product of two hats, (1 - |X - t_i| / h_i)(1 - |X - t_j| / h_j):
// over the two rows around X they add up to one, so the contact carries
// its load once, at X, shared by the particles on either side as a linear
// interpolation would share it, whichever particles X falls between.
// Symmetric under swapping i and j (then n, tau and alpha flip and
// t* -> d_t - t*).
//
// rate_i, rate_j: each curvature's rate of change along its particle's own
// tangent (-n_y, n_x) [1/m^2], the surfaces' cubic terms. An involute's
// curvature changes by a sixth across a 0.6 mm spacing at the paper's
// pitch point; a parabola of the particle's curvature then misses the
// flank by rate h^3 / 6, 1.7 um at the neighbouring particle, more than the
// contact's approach at 1 kN. Two neighbours' parabolas disagreed by that
// much where X fell between them, each pair's force followed its own
// overlap, and the load stuck to one particle (docs/contact.md). With the
// cubic terms X is where g' = 0 (Newton from the parabolas' t*, g'' > 0),
// and the curvatures in the formulas above are the local ones at X.
inline SurfacePair curved_surface_pair(double dx_ij, double dy_ij, double nix, double niy,
                                       double njx, double njy, double kappa_i, double kappa_j,
                                       double h_i, double h_j, double rate_i = 0.0,
                                       double rate_j = 0.0) {
  SurfacePair s;
  double nx = njx - nix, ny = njy - niy;
  const double len = std::sqrt(nx * nx + ny * ny);
  if (!(len > 1.41)) return s;  // not facing (surface_pair)
  nx /= len;
  ny /= len;
  const double tx = -ny, ty = nx;
  const double c = 0.5 * len;  // n_j . n, the cosine of either normal's tilt
  const double alpha = (njx * tx + njy * ty) / c;
  const double dn = dx_ij * nx + dy_ij * ny;
  // A convex parabola lies beyond its tangent line, a concave one (a flank
  // beside its root fillet) within it by at most |kappa| h^2 / 2 over its
  // hat, and over both hats |2 t - d_t| < h_i + h_j: apart by this bound,
  // the pair is apart (most candidates, before the curvature's work).
  // Without the concave term the bound cut pairs that overlapped, and their
  // energy went with them.
  const double stretch = (1.0 + alpha * alpha) * std::sqrt(1.0 + alpha * alpha);
  const double sag =
      std::min(kappa_i, 0.0) * h_i * h_i + std::min(kappa_j, 0.0) * h_j * h_j -
      (std::abs(rate_i) * h_i * h_i * h_i + std::abs(rate_j) * h_j * h_j * h_j) / 3.0;
  if (dn >= std::abs(alpha) * (h_i + h_j) - 0.5 * stretch * sag) return s;
  const double dt = dx_ij * tx + dy_ij * ty;
  const double ki = kappa_i * stretch, kj = kappa_j * stretch;
  // The cubic terms along tau: i's tangent is -tau, j's +tau (nearly).
  const double ci = rate_i * stretch * (nix * ty - niy * tx);
  const double cj = rate_j * stretch * (njx * ty - njy * tx);
  double t = (ki * dt - 2.0 * alpha) / (ki + kj);
  double ki_x = ki, kj_x = kj;  // the height functions' curvatures at t
  if (ci != 0.0 || cj != 0.0) {
    for (int it = 0; it < 4; ++it) {
      const double u = t - dt;
      ki_x = ki + ci * u;
      kj_x = kj + cj * t;
      const double slope_gap =
          2.0 * alpha + ki * u + 0.5 * ci * u * u + kj * t + 0.5 * cj * t * t;  // g'(t)
      t -= slope_gap / (ki_x + kj_x);
    }
    ki_x = ki + ci * (t - dt);
    kj_x = kj + cj * t;
  }
  const double k = ki_x + kj_x;
  const double hat_i = 1.0 - std::abs(t - dt) / h_i, hat_j = 1.0 - std::abs(t) / h_j;
  if (hat_i <= 0.0 || hat_j <= 0.0) return s;
  const double u = t - dt;
  const double g = dn + alpha * (2.0 * t - dt) + 0.5 * ki * u * u + ci * u * u * u / 6.0 +
                   0.5 * kj * t * t + cj * t * t * t / 6.0;
  if (g >= 0.0) return s;
  // The overlap's gradient in x_i - x_j: n - sigma tau, sigma = h_j'(t*)
  // the surfaces' common slope at X (their normal there, unnormalised).
  const double slope = -alpha - kj * t - 0.5 * cj * t * t;
  s.active = true;
  s.nx = nx - slope * tx;
  s.ny = ny - slope * ty;
  s.overlap = -g;
  s.weight = hat_i * hat_j;
  // X moves by k_i / K for a step of d_t (the local curvatures at X): the
  // hats' slopes.
  const double dhat_i = (t > dt ? 1.0 : -1.0) * (kj_x / k) / h_i;
  const double dhat_j = (t > 0.0 ? -1.0 : 1.0) * (ki_x / k) / h_j;
  s.tx = tx;
  s.ty = ty;
  s.dweight = dhat_i * hat_j + hat_i * dhat_j;
  return s;
}

// Whether a pair's surfaces are curved enough to have one contact point,
// convex together with a radius of curvature below a thousand spacings, and
// smooth enough for a parabola to stand for each: its tangent turns by less
// than kCornerTurning over the particle's spacing. Flatter pairs (the bars'
// faces) touch along their length, and a corner drawn by one particle (a
// rack tooth's tip rounding, 70 degrees over a spacing) is not a parabola:
// its tangent, extended, crossed a flank half a millimetre into the other
// tooth and pushed with 2 MN/m at the gear's first contact. Both stay with
// surface_pair.
constexpr double kCornerTurning = 0.6;  // rad
inline bool curved_pair(double kappa_i, double kappa_j, double h_i, double h_j) {
  return (kappa_i + kappa_j) * (h_i + h_j) > 1e-3 && std::abs(kappa_i) * h_i < kCornerTurning &&
         std::abs(kappa_j) * h_j < kCornerTurning;
}

}  // namespace gearsph::physics
