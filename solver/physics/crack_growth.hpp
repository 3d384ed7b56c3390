#pragma once
// Quasi-static crack growth by the maximum tangential stress criterion
// (Erdogan & Sih 1963, J. Basic Eng. 85, 519-527): the crack advances from
// its tip in the direction theta_c of the tip's frame (x1 along the
// crack's advance, x2 to its left, theta counter-clockwise from x1) in
// which the near-tip hoop stress
//
//   sigma_thth sqrt(2 pi r) = cos(theta/2) [K_I cos^2(theta/2) - 3/2 K_II sin(theta)]
//
// is greatest, i.e. where d sigma_thth / d theta = 0:
//
//   K_I sin(theta) + K_II (3 cos(theta) - 1) = 0.
//
// K_II's sign is that of the Williams field of diagnostics/stress_intensity.hpp
// (Anderson, Fracture Mechanics, table 2.2): K_II > 0 kinks the crack
// clockwise (theta_c < 0), 70.53 degrees in pure mode II.
#include <vector>

#include "solver/geometry/crack.hpp"

namespace gearsph::physics {

// The kink angle theta_c [rad] of the tip's frame: the root of the equation
// above on the branch of greatest hoop stress, 2 atan((K_I - sqrt(K_I^2 +
// 8 K_II^2)) / (4 K_II)). For an open crack (K_I >= 0) |theta_c| <= 70.53
// degrees: 0 in pure mode I, -/+ 70.53 degrees in pure mode II of sign +/-.
double max_tangential_stress_kink(double K_I, double K_II);

// The hoop stress of the near-tip field at theta, times sqrt(2 pi r)
// (Erdogan & Sih 1963, eq. 11): the quantity the kink maximises.
double near_tip_hoop_stress(double K_I, double K_II, double theta);

// The tip's new position: from `tip`, advancing along `direction` (a unit
// vector) turned by `kink` [rad], `increment` [m] further.
geometry::Point grown_tip(geometry::Point tip, geometry::Point direction, double kink,
                          double increment);

}  // namespace gearsph::physics

namespace gearsph::physics {

// The equivalent mode-I factor of the maximum tangential stress criterion:
// the near-tip hoop stress times sqrt(2 pi r) in the kink's direction, K_I
// itself in pure mode I.
double equivalent_K(double K_I, double K_II);

// Paris' law da/dN = C dK^m over a path of increments da[k] (from reading k
// to k + 1) with the equivalent K at every reading (one more than the
// increments), under a pulsating load (R = 0: dK = K_max): the cycles
// N = sum_k da[k] (f_k + f_{k+1}) / 2, f = 1 / (C dK^m), the trapezoidal
// rule in the crack length over each increment. dK in MPa m^0.5 and da in m,
// so C is in m/cycle per (MPa m^0.5)^m, as Paris constants are tabulated.
// An increment with a K <= 0 at either end is not growing: infinity.
double paris_cycles(const std::vector<double>& da_m, const std::vector<double>& K_eq_Pa_sqrt_m,
                    double C, double m);

}  // namespace gearsph::physics
