#pragma once
// Surface smoothing of the contact: where each particle touches and where
// its contact force goes.
//
// Why: a gear contact is narrower than a particle (Hertz half-width 0.08 mm
// at 1 kN against spacings of 0.3 - 1 mm), so the penalty law puts the whole
// load on one or two outline particles. A particle pushed alone by a point
// force meets little resistance from the SPH sums (its own stress does not
// change when it moves against neighbours that stay: the zero-energy
// pattern), so it sinks in and its neighbours pop out: in the seed paper's pinion
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
//   smoothed points  xs_i = sum_k W_ki x_k + R(theta_i) (X_i - sum_k W_ki X_k),
// theta_i the best-fit (Procrustes) rotation of the receivers,
// atan2(S, C) with C = sum W A_k . x_k, S = sum W A_k x x_k and
// A_k = X_k - sum W X. xs_i is then a function of the receivers' positions
// alone, and the force f_i found for particle i is its exact gradient: W_ki f_i
// on each k, plus the moment of the offset, M_i = o_i x f_i, as
// M_i dtheta_i/dx_k = W_ki M_i (C z x A_k - S A_k) / (C^2 + S^2) (for a
// rigid motion, W M / J z x (x_k - c) about the centroid). The contact is
// then conservative: through the bars' impact the energy balance stays
// within 1 % at every radius (`Contact.SpreadContactKeepsTheEnergy...`);
// turning the offset with the particle's own material rotation instead, as
// first done, added 30 % of the kinetic energy at a radius of 4-5 spacings
// and made the radius look as if it had to follow the body's size.
// Momentum is kept to round-off (sum_k W_ki = 1, the couple has no net
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
