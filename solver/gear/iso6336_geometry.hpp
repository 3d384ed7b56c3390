#pragma once
// The geometry of a cylindrical gear pair as ISO 6336 rates it: external
// spur and helical pairs (ISO 21771:2007 for the pair) and a pinion with its
// rack. A rack is a wheel of kRackTeeth teeth: every 1/z_2 term of ISO's
// formulas is then below 1e-6 of its neighbours, and u -> infinity. SI
// units (metres, radians); index 0 is the pinion, 1 the wheel or the rack.
#include <array>

namespace gearsph::gear::iso6336 {

inline constexpr int kRackTeeth = 1'000'000;

// The basic rack profile in module units (ISO 53:1998): the gear's
// addendum h_aP, the dedendum h_fP and root radius rho_fP (the generating
// tool's addendum and tip radius), and the residual undercut s_pr of a
// protuberance tool (ISO 6336-3:2006, eq. (18): pr - q; 0 without).
struct BasicRackProfile {
  double h_aP = 1.0;
  double h_fP = 1.25;
  double rho_fP = 0.38;
  double s_pr = 0.0;
};

struct PairSpec {
  double m_n = 0.0;      // normal module [m]
  double alpha_n = 0.0;  // normal pressure angle [rad]
  double beta = 0.0;     // helix angle at the reference circle [rad]
  double b = 0.0;        // common face width [m]
  std::array<int, 2> z{};
  std::array<double, 2> x{};    // profile shift coefficients
  std::array<double, 2> d_a{};  // tip diameters [m]; 0: d + 2 m_n (h_aP + x)
  // Form (start of involute) diameters [m]; 0: where the end of the tool's
  // straight flank generates it, not below the base circle. An undercut
  // gear's true form circle lies further out: give it.
  std::array<double, 2> d_Nf{};
  double a_w = 0.0;  // centre distance [m]; 0: from x_1 + x_2
  bool rack = false;
  BasicRackProfile tool;
};

struct PairGeometry {
  PairSpec spec;
  double alpha_t = 0.0, alpha_wt = 0.0, beta_b = 0.0;
  double a_w = 0.0, u = 0.0;
  std::array<double, 2> d{}, d_b{}, d_a{}, d_f{}, z_n{};
  std::array<double, 2> h{};  // tooth depth (d_a - d_f)/2
  std::array<double, 2> d_Nf{};
  double p_bt = 0.0;  // transverse base pitch
  // The active path of contact, from the pinion's base tangent point T1.
  double path_start = 0.0, path_end = 0.0;
  double eps_alpha = 0.0, eps_beta = 0.0, eps_gamma = 0.0;
  double eps_alpha_n = 0.0;  // of the virtual spur gears: eps_alpha / cos^2(beta_b)
  double rho_red = 0.0;      // relative radius of curvature at the pitch point (transverse)
};

// Throws InvalidRating (pointers under /pair and /gears) for a pair that has
// no involute contact: a tip inside the base circle, eps_alpha <= 1, a
// centre distance the profile shifts cannot reach. The path of contact runs
// between the tip circles, cut short where a form circle lies further out.
PairGeometry pair_geometry(const PairSpec& spec);

double involute(double angle);
// Inverse of involute() by Newton's method, for 0 <= inv < 1.
double inverse_involute(double inv);

}  // namespace gearsph::gear::iso6336
