#pragma once
// The unresolved near field of a contact: the Hertz line-contact compliance
// the particles cannot carry, as the surface model's normal law.
//
// Two flanks touching along a line carry a line load F' [N/m] over a strip
// of half-width a = sqrt(4 F' R* / (pi E*)) (Johnson 1985, eq. 4.43;
// 1/R* = kappa_i + kappa_j, the sum of the curvatures), a tenth of a
// particle spacing in a gear. The particles load each body by a traction
// spread over the surface around the contact (contact_smoothing.hpp) and
// measure the gap between the smoothed points; they represent every
// compliance coarser than that spread. What they miss is the difference
// between the Hertz pressure and the spread traction close to the contact.
// In plane strain a pressure q(s) on a half-plane moves its surface by
//   u(t) = -K F' int w(s) ln|t - s| ds + const,  K = 2 (1 - nu^2) / (pi E)
// (Johnson 1985, eq. 2.25b, w = q / F'), so between the Hertz centre,
// where int w ln|s| ds = ln(a/2) - 1/2, and the smoothed point of the spread
// traction, where the double log-moment of the weights is Lambda, the
// bodies' approaches differ by
//   delta_nf = sum_b K_b F' (Lambda_b - ln(a/2) + 1/2) = (A/2) F' ln(F0 / F'),
//   A = K_i + K_j = 2 / (pi E*),
//   F0 = (pi E* / (4 R*)) exp(2 sum_b K_b (Lambda_b + ln 2 + 1/2) / A).
// That is the overlap the pair law gives the load F': the contact is then as
// compliant as the continuum at any spacing. It is softest at small loads
// (like Hertz) and gains stiffness with ln F'; it would peak at F0 / e,
// where a nears the spread and the contact is resolved. The stiffness is
// bounded for the time step by k = kStiffSpring E* V / dx^2: the law follows
// delta_nf up to the load F* (< F0 / e) where its tangent stiffness reaches
// k, and continues along the spring's line beyond it, so below F* (every
// unresolved gear contact) the spring adds no compliance. Flat or concave pairs (1/R* <= 0) have no
// near field: the spring alone, a layer a third of a spacing thick.
//
// Lambda of a particle (contact_smoothing.hpp's weights W_k at reference
// points X_k, each standing for a stretch of surface Delta_k long):
//   Lambda = sum_{k != l} W_k W_l ln|X_k - X_l| + sum_k W_k^2 (ln Delta_k - 3/2),
// the self term being that of a uniform stretch. Without smoothing, a single
// particle: ln Delta - 3/2.
#include <algorithm>
#include <cmath>

#include "solver/physics/contact_seed_penalty.hpp"

namespace gearsph::physics {

// Peak pressure of a Hertz line contact carrying F' [N/m] between surfaces
// of curvatures adding up to `curvature` [1/m]: p0 = sqrt(F' E* / (pi R*))
// (Johnson 1985, eqs. 4.43 and 4.45), the basis of ISO 6336-2's sigma_H.
inline double hertz_peak_pressure(double load_per_m, double e_star, double curvature) {
  if (load_per_m <= 0.0 || curvature <= 0.0) return 0.0;
  return std::sqrt(load_per_m * e_star * curvature / 3.141592653589793);
}

// The stiffness bound in E* V / dx^2. Its contact oscillator must be slow
// enough for the step: at 10 the bars' impact at the default step (80 % of
// the elastic limit) gained 12 % of its kinetic energy through the time
// integration alone (1 % at a quarter of the step); at 3 it gains 1 %, and
// the bar impact's contact time is 1 % long at 0.5 mm (docs/contact.md).
constexpr double kStiffSpring = 3.0;

struct NearField {
  double half_a = 0.0;     // A / 2 = 1 / (pi E*)  [m/N]
  double f0 = 0.0;         // F0 [N/m]; 0: no near field
  double stiffness = 0.0;  // the stiffness bound k [N/m^2]
};

// e_star: contact modulus; k_i, k_j: 2 (1 - nu^2) / (pi E) of each body;
// lambda_i, lambda_j: their log-moments; curvature: kappa_i + kappa_j.
inline NearField near_field(double e_star, double k_i, double k_j, double lambda_i, double lambda_j,
                            double curvature, double spring) {
  NearField nf;
  const double a = k_i + k_j;
  nf.half_a = 0.5 * a;
  nf.stiffness = spring;
  if (curvature > 0.0) {
    constexpr double kLn2Half = 0.6931471805599453 + 0.5;
    const double b = k_i * (lambda_i + kLn2Half) + k_j * (lambda_j + kLn2Half);
    nf.f0 = 3.141592653589793 * e_star * curvature / 4.0 * std::exp(2.0 * b / a);
  }
  return nf;
}

namespace detail {
// delta_nf(F) and its slope, for 0 < F <= F* (below its peak at F0 / e).
inline void near_field_overlap(const NearField& nf, double f, double& delta, double& slope) {
  if (nf.f0 <= 0.0 || f <= 0.0) {
    delta = 0.0;
    slope = f <= 0.0 && nf.f0 > 0.0 ? 1e300 : 0.0;
    return;
  }
  const double l = std::log(nf.f0 / f);
  delta = nf.half_a * f * l;
  slope = nf.half_a * (l - 1.0);
}
}  // namespace detail

// The load F' [N/m] at which the near field's tangent stiffness reaches the
// spring's, 1 / delta_nf'(F*) = k: F* = F0 exp(-1 - 1 / (k A/2)); 0 without
// a near field.
inline double near_field_limit(const NearField& nf) {
  if (nf.f0 <= 0.0) return 0.0;
  return nf.f0 * std::exp(-1.0 - 1.0 / (nf.half_a * nf.stiffness));
}

// The load F' [N/m] for `overlap`, with the tangent stiffness dF'/d(overlap)
// and the stored energy int F' d(overlap). The overlap is the near field's,
// delta_nf(F'), up to F*, where its stiffness reaches the spring's; beyond
// it the spring's line continues: the stiffness never exceeds k (the time
// step's bound) and below F* the contact has exactly the continuum's
// compliance. Newton on the concave, increasing delta_nf from F*: the
// iterates stay below the root after the first step and rise to it.
inline PairLaw near_field_law(const NearField& nf, double overlap) {
  if (overlap <= 0.0) return {0.0, 0.0, 0.0};
  const double k = nf.stiffness;
  const double f_star = near_field_limit(nf);
  double d_star = 0.0, s = 0.0;
  if (f_star > 0.0) detail::near_field_overlap(nf, f_star, d_star, s);
  auto integral_nf = [&](double load) {  // int_0^load delta_nf, load <= F* < F0 / e
    if (load <= 0.0) return 0.0;
    return nf.half_a * (0.5 * load * load * std::log(nf.f0 / load) + 0.25 * load * load);
  };
  if (overlap >= d_star) {  // the spring's line
    const double f = f_star + (overlap - d_star) * k;
    const double energy = f * overlap - integral_nf(f_star) - d_star * (f - f_star) -
                          0.5 * (f - f_star) * (f - f_star) / k;
    return {f, k, energy};
  }
  double f = f_star, d = d_star;
  for (int it = 0; it < 60; ++it) {
    detail::near_field_overlap(nf, f, d, s);
    const double next = std::max(f - (d - overlap) / s, 1e-6 * f);
    if (std::abs(next - f) <= 1e-13 * f) {
      f = next;
      break;
    }
    f = next;
  }
  detail::near_field_overlap(nf, f, d, s);
  return {f, 1.0 / s, f * overlap - integral_nf(f)};
}

}  // namespace gearsph::physics
