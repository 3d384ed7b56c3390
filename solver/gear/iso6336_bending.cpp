#include "solver/gear/iso6336_bending.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace gearsph::gear::iso6336 {

namespace {

constexpr double kPi = std::numbers::pi;

// Slip-layer thickness rho' [mm] of ISO 6336-3:2006 Table 6. Steels and
// irons whose rho' falls with the yield strength are interpolated in it
// (St 300-400 MPa, V/GTS/GJS 500-1000 MPa), clamped at the table's ends;
// without a yield strength, the table's lowest strength of the class (the
// larger rho', the smaller Y_deltarelT for q_s < 2.5).
double slip_layer_mm(const GearMaterial& m) {
  const double y = m.yield_Pa / 1e6;
  auto interp = [](double x, const double* xs, const double* ys, int n) {
    if (x <= xs[0]) return ys[0];
    for (int k = 1; k < n; ++k) {
      if (x <= xs[k])
        return ys[k - 1] + (ys[k] - ys[k - 1]) * (x - xs[k - 1]) / (xs[k] - xs[k - 1]);
    }
    return ys[n - 1];
  };
  switch (m.cls) {
    case MaterialClass::GJL:
      return 0.3124;
    case MaterialClass::NT:
    case MaterialClass::NV:
      return 0.1005;
    case MaterialClass::Eh:
    case MaterialClass::IF:
      return 0.0030;
    case MaterialClass::St: {
      static const double xs[] = {300, 400}, ys[] = {0.0833, 0.0445};
      return interp(y, xs, ys, 2);
    }
    default: {
      static const double xs[] = {500, 600, 800, 1000}, ys[] = {0.0281, 0.0194, 0.0064, 0.0014};
      return interp(y, xs, ys, 4);
    }
  }
}

}  // namespace

IsoToothForm virtual_tooth_form(const ToothFormInput& in) {
  const double m = in.m_n, alpha = in.alpha_n, z = in.z_n, x = in.x;
  const double h_fp = in.tool.h_fP, rho_fp = in.tool.rho_fP;
  // E, G, H and the 30-degree tangent angle theta, in module units.
  const double E = kPi / 4.0 - h_fp * std::tan(alpha) + in.tool.s_pr / std::cos(alpha) -
                   (1.0 - std::sin(alpha)) * rho_fp / std::cos(alpha);
  const double G = rho_fp - h_fp + x;
  const double H = 2.0 / z * (kPi / 2.0 - E) - kPi / 3.0;
  double theta = kPi / 6.0;
  for (int it = 0; it < 50; ++it) theta = 2.0 * G / z * std::tan(theta) - H;
  IsoToothForm f;
  f.theta = theta;
  f.s_Fn = m * (z * std::sin(kPi / 3.0 - theta) + std::sqrt(3.0) * (G / std::cos(theta) - rho_fp));
  f.rho_F =
      m * (rho_fp + 2.0 * G * G / (std::cos(theta) * (z * std::pow(std::cos(theta), 2) - 2.0 * G)));
  // Load at d_en: pressure angle alpha_en there, half tooth angle gamma_e,
  // load angle alpha_Fen = alpha_en - gamma_e, bending arm h_Fe.
  const double d_bn = m * z * std::cos(alpha);
  f.load_radius = 0.5 * in.d_en;
  const double alpha_en = std::acos(d_bn / in.d_en);
  const double gamma_e =
      (kPi / 2.0 + 2.0 * x * std::tan(alpha)) / z + involute(alpha) - involute(alpha_en);
  f.alpha_Fen = alpha_en - gamma_e;
  f.h_Fe = 0.5 * m *
           ((std::cos(gamma_e) - std::sin(gamma_e) * std::tan(f.alpha_Fen)) * in.d_en / m -
            z * std::cos(kPi / 3.0 - theta) - G / std::cos(theta) + rho_fp);
  f.Y_F = (6.0 * f.h_Fe / m * std::cos(f.alpha_Fen)) / (std::pow(f.s_Fn / m, 2) * std::cos(alpha));
  const double L = f.s_Fn / f.h_Fe, q_s = f.s_Fn / (2.0 * f.rho_F);
  f.Y_S = (1.2 + 0.13 * L) * std::pow(q_s, 1.0 / (1.21 + 2.3 / L));
  return f;
}

double outer_single_contact_diameter(const PairGeometry& g, int k) {
  const PairSpec& s = g.spec;
  const double d_n = s.m_n * g.z_n[k];
  const double r_bn = 0.5 * d_n * std::cos(s.alpha_n);
  const double p_bn = kPi * s.m_n * std::cos(s.alpha_n);
  // The tip of the virtual gear, or the end of the active path where the
  // mate's form circle cuts it short (the transverse shortfall, taken over).
  const double T1T2 = g.a_w * std::sin(g.alpha_wt);
  const double end = k == 0 ? g.path_end : T1T2 - g.path_start;
  const double tip_t = 0.5 * std::sqrt(g.d_a[k] * g.d_a[k] - g.d_b[k] * g.d_b[k]);
  const double shortfall = (tip_t - end) / std::cos(g.beta_b);
  const double r_an = 0.5 * (d_n + g.d_a[k] - g.d[k]);
  const double from_tip =
      std::sqrt(r_an * r_an - r_bn * r_bn) - shortfall - p_bn * (g.eps_alpha_n - 1.0);
  return 2.0 * std::sqrt(from_tip * from_tip + r_bn * r_bn);
}

double helix_factor(const PairGeometry& g) {
  const double eb = std::min(g.eps_beta, 1.0);
  const double beta_deg = std::min(g.spec.beta * 180.0 / kPi, 30.0);
  return 1.0 - eb * beta_deg / 120.0;
}

double rim_factor(double rim_m, double h_t) {
  if (rim_m <= 0.0) return 1.0;
  const double r = rim_m / h_t;
  if (r < 0.5) return std::numeric_limits<double>::quiet_NaN();  // outside ISO's range
  return r >= 1.2 ? 1.0 : 1.6 * std::log(2.242 / r);
}

double deep_tooth_factor(double eps_alpha_n, int grade) {
  if (eps_alpha_n <= 2.05 || grade > 4) return 1.0;
  return eps_alpha_n > 2.5 ? 0.9 : -0.666 * eps_alpha_n + 2.366;
}

double notch_sensitivity_factor(const GearMaterial& m, double q_s) {
  const double rho = slip_layer_mm(m);
  const double chi = (1.0 + 2.0 * q_s) / 5.0;    // relative stress gradient [1/mm]
  const double chi_T = (1.0 + 2.0 * 2.5) / 5.0;  // of the test gear, q_s = 2.5
  return (1.0 + std::sqrt(rho * chi)) / (1.0 + std::sqrt(rho * chi_T));
}

double surface_factor(const GearMaterial& m, double Rz) {
  const bool smooth = Rz < 1.0;
  // ISO 6336-3:2006, Table 7: St its own line; GJL with the nitrided
  // steels; V, GJS, GTS, Eh, IF the third.
  switch (m.cls) {
    case MaterialClass::St:
      return smooth ? 1.070 : 5.306 - 4.203 * std::pow(Rz + 1.0, 0.01);
    case MaterialClass::GJL:
    case MaterialClass::NT:
    case MaterialClass::NV:
      return smooth ? 1.025 : 4.299 - 3.259 * std::pow(Rz + 1.0, 0.0058);
    default:
      return smooth ? 1.120 : 1.674 - 0.529 * std::pow(Rz + 1.0, 0.1);
  }
}

double size_factor(const GearMaterial& m, double m_n_m) {
  const double mn = m_n_m * 1e3;
  if (mn <= 5.0) return 1.0;
  if (m.cls == MaterialClass::GJL) return mn >= 25.0 ? 0.7 : 1.075 - 0.015 * mn;
  if (surface_hardened(m.cls)) return mn >= 25.0 ? 0.8 : 1.05 - 0.01 * mn;
  return mn >= 30.0 ? 0.85 : 1.03 - 0.006 * mn;
}

}  // namespace gearsph::gear::iso6336
