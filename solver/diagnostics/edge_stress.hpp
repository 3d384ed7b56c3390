#pragma once
// The stress along a boundary from the boundary's own stretch.
//
// Where the traction on a boundary is known (zero on a free edge: a fillet,
// a hole; a pressure on a bore), the in-plane stress there has one unknown,
// the tangential stress sigma_tt, and Hooke's law in plane strain gives it
// from the tangential strain of the boundary itself:
//
//   eps_tt = ((1 - nu^2) sigma_tt - nu (1 + nu) sigma_nn) / E
//   sigma_tt = E / (1 - nu^2) eps_tt + nu / (1 - nu) sigma_nn
//
// The strain is the stretch of the curve, eps_tt = |dx/ds| / |dX/ds| - 1,
// with x = X + u, so a rigid rotation, however large, gives none. This is
// how a strain gauge on the fillet reads it, and how a finite-element code
// would if it differentiated its nodal displacements along the edge: the
// displacement converges an order faster than the stress, and a tangential
// derivative along the curve does not reach across the boundary as a fit of
// the stress tensor must. The boundary condition sigma n = t holds by
// construction, where a recovered stress tensor carries a spurious sigma_nn.
//
// The derivative is taken by a least-squares quadratic in arc length over
// the points within `window` of each point (one-sided at the ends of an
// open curve), of X and of x alike, so that the curvature of the outline
// cancels in the ratio.
#include <vector>

#include "solver/geometry/polygon.hpp"

namespace gearsph::diagnostics {

struct EdgeCurve {
  std::vector<geometry::Point> reference;     // X along the curve, in order [m]
  std::vector<geometry::Point> displacement;  // u = x - X at the same points [m]
  std::vector<double> arc;                    // arc length, increasing [m]
  bool closed = false;                        // the last point joins the first
};

// sigma_tt [Pa] at every point of the curve; `normal_stress` (optional, one
// per point, tension positive) is the known sigma_nn, zero when absent.
std::vector<double> edge_tangential_stress(const EdgeCurve& curve, double window, double E,
                                           double nu,
                                           const std::vector<double>* normal_stress = nullptr);

}  // namespace gearsph::diagnostics
