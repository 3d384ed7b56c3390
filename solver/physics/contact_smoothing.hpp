#pragma once
// Surface smoothing of the contact: where each particle touches and where
// its contact force goes.
//
// Why: a gear contact is narrower than a particle (Hertz half-width 0.08 mm
// at 1 kN against spacings of 0.3 - 1 mm), so the penalty law puts the whole
// load on one or two outline particles. A particle pushed alone by a point
// force meets little resistance from the SPH sums (its own stress does not
// change when it moves against neighbours that stay: the zero-energy
// pattern), so it sinks in and its neighbours pop out: in the paper's pinion
// at 1 kN the loaded particle moved 2 um further than the material 1 mm
// below it, against 0.4 um for a continuum (Flamant, Johnson 1985 eq. 2.19a
// between depths a and 1 mm); the mesh stiffness came out near half of ISO's.
//
// The remedy is what finite elements do with a point load on a surface: the
// force is shared by the surface around the point as a smooth traction.
// Each surface particle i carries a partition of unity W_ki over the surface
// particles k of its body within R = smoothing_spacings x spacing_i (a
// Wendland C2 profile of the reference distance, normals within 60 degrees),
// normalised so that sum_k W_ki = 1. The contact law then acts between
//   smoothed points  xs_i = sum_k W_ki x_k + R_i (X_i - sum_k W_ki X_k)
// (R_i the material rotation, from the turned normal), and the force f_i
// found for particle i is applied to each k as W_ki f_i plus its share of
// the couple of the offset o_i = R_i (X_i - sum W X): a moment
// M_i = o_i x f_i spread as W_ki M_i / J_i z x (x_k - c_i) about the
// centroid c_i, J_i = sum_k W_ki |x_k - c_i|^2. The spread force is then
// the gradient of the same penalty energy also while the body turns (the
// offset turns with it; without the couple the loaded gear gained energy),
// momentum is kept to round-off (sum_k W_ki = 1, the couple has no net
// force) and a rigid motion moves xs_i with x_i.
//
// What it does not do: it does not resolve the Hertz pressure under a
// contact narrower than R; the pressure read from the particles is the
// penalty's, smoothed over R. A contact resolved by several spacings
// (the `hertz` scene at a/6) needs no smoothing and switches it off.
#include <cmath>

namespace gearsph::physics {

// Wendland C2 profile of q = r / R on [0, 1].
inline double smoothing_weight(double q) {
  if (q >= 1.0) return 0.0;
  const double a = 1.0 - q, a2 = a * a;
  return a2 * a2 * (1.0 + 4.0 * q);
}

// Neighbours whose outward normals differ by more than 60 degrees (a tooth
// tip's other flank) are not on the same stretch of surface.
constexpr double kSmoothingNormalCosine = 0.5;

}  // namespace gearsph::physics
