#pragma once
// Stress (and displacement) at points of the body, recovered from the
// particles around them by a moving least-squares fit, the meshfree
// counterpart of the way finite-element codes extrapolate integration-point
// stresses to nodes (Zienkiewicz & Zhu 1992, superconvergent patch
// recovery; Lancaster & Salkauskas 1981 for the moving least squares).
//
// At a query point q the stress field is fitted, component by component,
// by a polynomial p(X - q) of order 1 (or 2) in the reference coordinates,
// weighting each particle j of the body by the bell (1 - (r/R)^2)^3 of its
// distance r = |X_j - q|, R = 3 s_q (s_q the spacing of the particle nearest
// q: the support of the default kernel); the value is p(0). On a body-fitted outline the particles
// of the outline row lie on the curve, so a point of the outline is interpolated along it and needs
// no extrapolation across it. A single particle's zig-zag or the staircase of a lattice is averaged
// out over the support, and the fit follows a linear (quadratic) gradient exactly.
//
// The default order is 2: a peak along a curved boundary (a fillet, a hole)
// is concave, and a linear fit over a support of three spacings flattens it
// (Kirsch at a/10: -5.5 % with order 1, docs/method.md).
//
// Loaded boundaries: a particle of the outline row that carries an applied
// traction as a force balances it against the pair forces of its
// neighbourhood, but its own stress, from the displacement gradient around
// it, does not satisfy sigma n = t (nodal integration does not pass the
// patch test at a boundary; Chen et al. 2001, IJNME 50). On a thick cylinder
// the bore row's radial stress is half the pressure and its hoop stress
// 13 % high, while the rows inside are within 1-3 % of Lame. Such rows are
// left out of the fit (`skip`), and the point is extrapolated from inside.
//
// Reference coordinates (X = x0): query points are given on the undeformed
// outline. The in-plane stress is the Cauchy stress in the current frame, so
// for a rotating body read invariants (principal stresses) or rotate it.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/geometry/polygon.hpp"

namespace gearsph {
struct Simulation;
}

namespace gearsph::diagnostics {

struct RecoveredStress {
  double xx = 0.0, yy = 0.0, xy = 0.0, zz = 0.0;  // Cauchy stress [Pa]
  double ux = 0.0, uy = 0.0;                      // displacement x - X [m]
  std::size_t neighbours = 0;                     // particles in the fit
  bool ok = false;                                // the fit was well posed
};

class StressRecovery {
 public:
  // Query points of one body (`body` index) in reference coordinates; the
  // neighbourhoods and weights are found once here and reused at every call
  // of recover() (the particles' reference positions never change).
  // `skip` (optional, one flag per particle): particles left out of every
  // fit, such as the outline row that carries an applied traction (its own
  // stress does not see the load: see the class comment).
  StressRecovery(const Simulation& sim, int body, const std::vector<geometry::Point>& points,
                 int order = 2, const std::vector<std::uint8_t>* skip = nullptr);
  std::vector<RecoveredStress> recover(const Simulation& sim) const;
  std::size_t size() const { return fits_.size(); }

 private:
  // Per query point: its particles and the weights that turn their values
  // into the fitted value at the point (p(0) is linear in the data).
  struct Fit {
    std::vector<std::size_t> particles;
    std::vector<double> weights;
    bool ok = false;
  };
  std::vector<Fit> fits_;
};

}  // namespace gearsph::diagnostics
