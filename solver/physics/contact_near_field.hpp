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
// (like Hertz) and gains stiffness with ln F'. Once a nears the spread
// (F' > F0 / e, where delta_nf would start to fall) the contact is resolved
// and delta_nf is held at its peak. A stiff spring in series,
// k = kStiffSpring E* V / dx^2, bounds the stiffness for the time step; its
// compliance is that of a layer a tenth of a spacing thick. Flat or concave
// pairs (1/R* <= 0) have no near field: the stiff spring alone.
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

// The series spring's stiffness in E* V / dx^2 (the paper's D = 1 gave a
// contact three times as compliant as the continuum's near field).
constexpr double kStiffSpring = 10.0;

struct NearField {
  double half_a = 0.0;     // A / 2 = 1 / (pi E*)  [m/N]
  double f0 = 0.0;         // F0 [N/m]; 0: no near field
  double stiffness = 0.0;  // series spring [N/m^2]
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
// delta_nf(F) and its slope, held at the peak beyond F0 / e.
inline void near_field_overlap(const NearField& nf, double f, double& delta, double& slope) {
  const double knee = nf.f0 / 2.718281828459045;
  if (nf.f0 <= 0.0 || f <= 0.0) {
    delta = 0.0;
    slope = f <= 0.0 && nf.f0 > 0.0 ? 1e300 : 0.0;
    return;
  }
  if (f >= knee) {
    delta = nf.half_a * knee;
    slope = 0.0;
    return;
  }
  const double l = std::log(nf.f0 / f);
  delta = nf.half_a * f * l;
  slope = nf.half_a * (l - 1.0);
}
}  // namespace detail

// The load F' [N/m] whose near field plus series spring give `overlap`,
// with the tangent stiffness dF'/d(overlap) and the stored energy
// int F' d(overlap). Newton on the concave, increasing overlap(F'), from
// the spring-only load (an upper bound): the iterates stay below the root
// after the first step and rise to it.
inline PairLaw near_field_law(const NearField& nf, double overlap) {
  if (overlap <= 0.0) return {0.0, 0.0, 0.0};
  const double inv_k = 1.0 / nf.stiffness;
  double f = overlap * nf.stiffness;
  double d = 0.0, s = 0.0;
  for (int it = 0; it < 40; ++it) {
    detail::near_field_overlap(nf, f, d, s);
    const double residual = d + f * inv_k - overlap;
    const double step = residual / (s + inv_k);
    const double next = std::max(f - step, 1e-6 * f);
    if (std::abs(next - f) <= 1e-13 * f) {
      f = next;
      break;
    }
    f = next;
  }
  detail::near_field_overlap(nf, f, d, s);
  // Energy: F delta - int_0^F delta(F') dF'.
  const double knee = nf.f0 / 2.718281828459045;
  auto integral_nf = [&](double load) {  // int_0^load delta_nf
    if (nf.f0 <= 0.0) return 0.0;
    const double g = std::min(load, knee);
    double v = nf.half_a * (0.5 * g * g * std::log(nf.f0 / g) + 0.25 * g * g);
    if (load > knee) v += nf.half_a * knee * (load - knee);
    return v;
  };
  const double energy = f * overlap - integral_nf(f) - 0.5 * f * f * inv_k;
  return {f, 1.0 / (s + inv_k), energy};
}

}  // namespace gearsph::physics
