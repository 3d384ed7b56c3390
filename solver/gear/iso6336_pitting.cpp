#include "solver/gear/iso6336_pitting.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gearsph::gear::iso6336 {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMPa = 1e6;

// C_ZL of clause 11 by sigma_Hlim [MPa]; C_Zv = C_ZL + 0.02.
double c_ZL(double s) {
  if (s < 850.0) return 0.83;
  if (s > 1200.0) return 0.91;
  return s / 4375.0 + 0.6357;
}

// M_1 (pinion) and M_2 (wheel) of clause 6.2: the relative radii of
// curvature at the pitch point over those at the inner points of single
// contact of each gear.
std::array<double, 2> curvature_ratios(const PairGeometry& g) {
  std::array<double, 2> M{};
  for (int k = 0; k < 2; ++k) {
    const int o = 1 - k;
    const double own = std::sqrt(std::pow(g.d_a[k] / g.d_b[k], 2) - 1.0) - 2.0 * kPi / g.spec.z[k];
    const double other = std::sqrt(std::pow(g.d_a[o] / g.d_b[o], 2) - 1.0) -
                         (g.eps_alpha - 1.0) * 2.0 * kPi / g.spec.z[o];
    M[k] = std::tan(g.alpha_wt) / std::sqrt(own * other);
  }
  return M;
}

}  // namespace

double zone_factor(const PairGeometry& g) {
  return std::sqrt(2.0 * std::cos(g.beta_b) * std::cos(g.alpha_wt) /
                   (std::pow(std::cos(g.alpha_t), 2) * std::sin(g.alpha_wt)));
}

double elasticity_factor(const GearMaterial& m1, const GearMaterial& m2) {
  const double s = (1.0 - m1.nu * m1.nu) / m1.E_Pa + (1.0 - m2.nu * m2.nu) / m2.E_Pa;
  return std::sqrt(1.0 / (kPi * s));
}

double contact_ratio_factor(const PairGeometry& g) {
  const double ea = g.eps_alpha, eb = g.eps_beta;
  if (eb >= 1.0) return std::sqrt(1.0 / ea);
  return std::sqrt((4.0 - ea) / 3.0 * (1.0 - eb) + eb / ea);
}

double helix_angle_factor(const PairGeometry& g) {
  return 1.0 / std::sqrt(std::cos(g.spec.beta));
}

std::array<double, 2> single_pair_factors(const PairGeometry& g) {
  const std::array<double, 2> M = curvature_ratios(g);
  std::array<double, 2> Z{1.0, 1.0};
  if (g.eps_beta >= 1.0) return Z;
  for (int k = 0; k < 2; ++k) {
    // Spur gears take M; helical gears with eps_beta < 1 interpolate to 1.
    if (M[k] > 1.0) Z[k] = M[k] - g.eps_beta * (M[k] - 1.0);
  }
  return Z;
}

double lubricant_factor(double sigma_Hlim_Pa, double nu40) {
  const double c = c_ZL(sigma_Hlim_Pa / kMPa);
  return c + 4.0 * (1.0 - c) / std::pow(1.2 + 134.0 / nu40, 2);
}

double velocity_factor(double sigma_Hlim_Pa, double v) {
  const double c = c_ZL(sigma_Hlim_Pa / kMPa) + 0.02;
  return c + 2.0 * (1.0 - c) / std::sqrt(0.8 + 32.0 / v);
}

double roughness_factor(double sigma_Hlim_Pa, double Rz1, double Rz2, double rho_red_m) {
  const double s = sigma_Hlim_Pa / kMPa;
  const double c = s < 850.0 ? 0.15 : s > 1200.0 ? 0.08 : 0.32 - 0.0002 * s;
  // Mean peak-to-valley roughness of the pair at a relative radius of 10 mm.
  const double Rz10 = 0.5 * (Rz1 + Rz2) * std::cbrt(10.0 / (rho_red_m * 1e3));
  return std::pow(3.0 / Rz10, c);
}

std::array<double, 2> work_hardening_factors(const PairGeometry& g,
                                             const std::array<GearMaterial, 2>& mat,
                                             const std::array<double, 2>& Rz, double nu40,
                                             double v) {
  std::array<double, 2> Z{1.0, 1.0};
  for (int k = 0; k < 2; ++k) {
    const int o = 1 - k;
    if (surface_hardened(mat[k].cls) || !surface_hardened(mat[o].cls)) continue;
    const double HB =
        std::clamp(mat[k].hardness_HB > 0.0 ? mat[k].hardness_HB : 130.0, 130.0, 470.0);
    // Equivalent roughness of the hard flank, clamped to the 3..16 um of ISO's data.
    const double R_zH =
        std::clamp(Rz[o] * std::pow(10.0 / (g.rho_red * 1e3), 0.33) *
                       std::pow(Rz[o] / Rz[k], 0.66) / std::pow(nu40 * v / 1500.0, 0.33),
                   3.0, 16.0);
    Z[k] = (1.2 - (HB - 130.0) / 1700.0) * std::pow(3.0 / R_zH, 0.15);
  }
  return Z;
}

double nominal_contact_stress(const PairGeometry& g, double F_t, double Z_H, double Z_E,
                              double Z_eps, double Z_beta) {
  const double ratio = g.spec.rack ? 1.0 : (g.u + 1.0) / g.u;
  return Z_H * Z_E * Z_eps * Z_beta * std::sqrt(F_t / (g.d[0] * g.spec.b) * ratio);
}

}  // namespace gearsph::gear::iso6336
