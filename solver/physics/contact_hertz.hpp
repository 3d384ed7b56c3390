#pragma once
// A Hertz-type contact penalty: two particles are treated as elastic spheres
// of diameter dx; the 3D Hertz law F = (4/3) E* sqrt(R*) delta^(3/2)
// (R* = dx/4 for two spheres of radius dx/2; Johnson 1985, eq. 4.22), spread
// over the particle's thickness dx to give a force per unit thickness:
//   F_ij = (4/3) E* sqrt(dx/4) delta^(3/2) / dx,  delta = r0 - r.
// It stiffens with the overlap instead of the linear seed_penalty law; the
// stability study compares the two.
#include <cmath>

#include "solver/physics/contact_seed_penalty.hpp"

namespace gearsph::physics {

inline PairLaw hertz_penalty(double e_star, double dx, double overlap) {
  const double k = (4.0 / 3.0) * e_star * std::sqrt(0.25 * dx) / dx;
  const double s = std::sqrt(overlap);
  return {k * overlap * s, 1.5 * k * s, 0.4 * k * overlap * overlap * s};
}

}  // namespace gearsph::physics
