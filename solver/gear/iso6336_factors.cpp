#include "solver/gear/iso6336_factors.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gearsph::gear::iso6336 {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMm = 1e3;  // metres to millimetres

bool through_hardened(MaterialClass c) {
  return c == MaterialClass::St || c == MaterialClass::V || c == MaterialClass::GJS ||
         c == MaterialClass::GTS;
}

// Running-in allowance of one gear for a deviation, ISO 6336-1:2006: 160 /
// sigma_Hlim of it for steels and nodular iron (capped above 5 m/s), 0.275
// of it for grey iron, 0.075 of it (at most 3 um) for surface-hardened gears.
double allowance_one(const GearMaterial& m, double dev_um, double v) {
  const double s_Hlim = m.sigma_Hlim_Pa / 1e6;
  if (through_hardened(m.cls)) {
    const double y = 160.0 / s_Hlim * dev_um;
    if (v > 10.0) return std::min(y, 6400.0 / s_Hlim);
    if (v > 5.0) return std::min(y, 12800.0 / s_Hlim);
    return y;
  }
  if (m.cls == MaterialClass::GJL) {
    const double y = 0.275 * dev_um;
    return v > 10.0 ? std::min(y, 11.0) : v > 5.0 ? std::min(y, 22.0) : y;
  }
  return std::min(0.075 * dev_um, 3.0);
}

// The same for the helix: 320 / sigma_Hlim, 0.55 and 0.15 (at most 6 um)
// of the initial equivalent misalignment F_betax.
double helix_allowance_one(const GearMaterial& m, double F_betax, double v) {
  const double s_Hlim = m.sigma_Hlim_Pa / 1e6;
  if (through_hardened(m.cls)) {
    const double y = 320.0 / s_Hlim * F_betax;
    if (v > 10.0) return std::min(y, 12800.0 / s_Hlim);
    if (v > 5.0) return std::min(y, 25600.0 / s_Hlim);
    return y;
  }
  if (m.cls == MaterialClass::GJL) {
    const double y = 0.55 * F_betax;
    return v > 10.0 ? std::min(y, 22.0) : v > 5.0 ? std::min(y, 45.0) : y;
  }
  return std::min(0.15 * F_betax, 6.0);
}

// Reduced mass of the pair per unit face width [kg/mm] of solid gears:
// m* = J*/r_b^2 = pi rho d_m^4 / (8 d_b^2) each (ISO 6336-1:2006, 6.5.9).
double reduced_mass(const PairGeometry& g, const std::array<GearMaterial, 2>& mat) {
  double inv = 0.0;
  for (int k = 0; k < 2; ++k) {
    const double d_m = 0.5 * (g.d_a[k] + g.d_f[k]) * kMm;
    const double rho = mat[k].rho_kg_m3 * 1e-9;  // kg/mm^3
    inv += 8.0 * std::pow(g.d_b[k] * kMm, 2) / (kPi * rho * std::pow(d_m, 4));
  }
  return 1.0 / inv;
}

// Table 8 of ISO 6336-1:2006: the coefficients C_v1..C_v7 by eps_gamma.
struct DynamicCoefficients {
  double c1 = 0.32, c2, c3, c4, c5 = 0.47, c6, c7;
};
DynamicCoefficients dynamic_coefficients(double eg) {
  DynamicCoefficients c;
  if (eg <= 2.0) {
    c.c2 = 0.34, c.c3 = 0.23, c.c4 = 0.90, c.c6 = 0.47;
  } else {
    c.c2 = 0.57 / (eg - 0.3), c.c3 = 0.096 / (eg - 1.56);
    c.c4 = (0.57 - 0.05 * eg) / (eg - 1.44), c.c6 = 0.12 / (eg - 1.74);
  }
  c.c7 = eg <= 1.5 ? 0.75 : eg <= 2.5 ? 0.125 * std::sin(kPi * (eg - 2.0)) + 0.875 : 1.0;
  return c;
}

}  // namespace

GradeTolerances grade_tolerances(int grade, double m_n_mm, double d_mm, double b_mm) {
  const double step = std::pow(std::sqrt(2.0), grade - 5);
  GradeTolerances t;
  t.f_pt_um = (0.001 * d_mm + 0.4 * m_n_mm + 5.0) * step;
  t.f_falpha_um = (0.55 * m_n_mm + 5.0) * step;
  t.f_Hbeta_um = (0.07 * std::sqrt(d_mm) + 0.45 * std::sqrt(b_mm) + 3.0) * step;
  return t;
}

double theoretical_single_stiffness(double z_n1, double inv_z_n2, double x1, double x2) {
  // q' [mm um/N], ISO 6336-1:2006 method B (coefficients C1..C9).
  const double q = 0.04723 + 0.15551 / z_n1 + 0.25791 * inv_z_n2 - 0.00635 * x1 -
                   0.11654 * x1 / z_n1 - 0.00193 * x2 - 0.24188 * x2 * inv_z_n2 +
                   0.00529 * x1 * x1 + 0.00182 * x2 * x2;
  return 1.0 / q;
}

double basic_rack_factor(double h_fP, double alpha_n) {
  const double alpha_deg = alpha_n * 180.0 / kPi;
  return (1.0 + 0.5 * (1.2 - h_fP)) * (1.0 - 0.02 * (20.0 - alpha_deg));
}

MeshStiffness mesh_stiffness(const PairGeometry& g, const std::array<GearMaterial, 2>& mat,
                             double w) {
  const PairSpec& s = g.spec;
  MeshStiffness c;
  const double inv_z2 = s.rack ? 0.0 : 1.0 / g.z_n[1];
  c.c_th = theoretical_single_stiffness(g.z_n[0], inv_z2, s.x[0], s.rack ? 0.0 : s.x[1]);
  c.q_prime = 1.0 / c.c_th;
  c.C_B = basic_rack_factor(s.tool.h_fP, s.alpha_n);
  // Other materials than steel: E = 2 E1 E2 / (E1 + E2) over E_st.
  c.E_ratio = 2.0 * mat[0].E_Pa * mat[1].E_Pa / (mat[0].E_Pa + mat[1].E_Pa) / kSteelModulusPa;
  // Below 100 N/mm of line load the teeth are softer: (w/100)^0.25.
  c.load_correction = w < 100.0 ? std::pow(w / 100.0, 0.25) : 1.0;
  constexpr double kCR = 1.0;  // solid blanks
  c.c_prime = c.c_th * kStiffnessCorrection * kCR * c.C_B * std::cos(s.beta) * c.E_ratio *
              c.load_correction;
  c.c_gamma_alpha = c.c_prime * (0.75 * g.eps_alpha + 0.25);
  c.c_gamma_beta = 0.85 * c.c_gamma_alpha;
  return c;
}

double running_in_allowance(const std::array<GearMaterial, 2>& mat, double dev_um, double v) {
  return 0.5 * (allowance_one(mat[0], dev_um, v) + allowance_one(mat[1], dev_um, v));
}

DynamicFactor dynamic_factor(const PairGeometry& g, const std::array<GearMaterial, 2>& mat,
                             const MeshStiffness& c, const Deviations& dev, double n1_rpm, double w,
                             double v) {
  DynamicFactor k;
  k.m_red_kg_mm = reduced_mass(g, mat);
  k.n_E1_rpm = 30000.0 / (kPi * g.spec.z[0]) * std::sqrt(c.c_gamma_alpha / k.m_red_kg_mm);
  k.N = n1_rpm / k.n_E1_rpm;
  k.N_S = w < 100.0 ? 0.5 + 0.35 * std::sqrt(w / 100.0) : 0.85;
  k.y_alpha_um = running_in_allowance(mat, dev.f_pb_um, v);
  k.y_f_um = running_in_allowance(mat, dev.f_falpha_um, v);
  k.B_p = c.c_prime * std::max(0.0, dev.f_pb_um - k.y_alpha_um) / w;
  k.B_f = c.c_prime * std::max(0.0, dev.f_falpha_um - k.y_f_um) / w;
  k.B_k = std::abs(1.0 - c.c_prime * dev.C_a_um / w);
  const DynamicCoefficients cv = dynamic_coefficients(g.eps_gamma);
  const double main = cv.c1 * k.B_p + cv.c2 * k.B_f + cv.c4 * k.B_k + 1.0;
  const double super = cv.c5 * k.B_p + cv.c6 * k.B_f + cv.c7;
  if (k.N <= k.N_S) {
    k.K_v = k.N * (cv.c1 * k.B_p + cv.c2 * k.B_f + cv.c3 * k.B_k) + 1.0;
    k.range = "subcritical";
  } else if (k.N <= 1.15) {
    k.K_v = main;
    k.range = "main resonance";
  } else if (k.N < 1.5) {
    k.K_v = super + (main - super) * (1.5 - k.N) / 0.35;
    k.range = "intermediate";
  } else {
    k.K_v = super;
    k.range = "supercritical";
  }
  return k;
}

FaceLoadFactor face_load_factor(const PairGeometry& g, const std::array<GearMaterial, 2>& mat,
                                const MeshStiffness& c, const Deviations& dev, double F_m, double v,
                                double F_betax_um, double K_Hbeta_given) {
  FaceLoadFactor f;
  const double b_mm = g.spec.b * kMm, w_m = F_m / b_mm;
  if (K_Hbeta_given > 0.0) {
    f.K_Hbeta = K_Hbeta_given;
    f.K_Hbeta_from = "given";
  } else {
    f.f_sh_um = w_m * 0.023 * std::pow(g.spec.b / g.d[0], 2);
    f.f_ma_um = std::hypot(dev.f_Hbeta_um[0], dev.f_Hbeta_um[1]);
    const double minimum =
        std::max(0.005 * w_m, 0.5 * std::max(dev.f_Hbeta_um[0], dev.f_Hbeta_um[1]));
    f.F_betax_um = F_betax_um > 0.0 ? F_betax_um : std::max(1.33 * f.f_sh_um + f.f_ma_um, minimum);
    f.y_beta_um = 0.5 * (helix_allowance_one(mat[0], f.F_betax_um, v) +
                         helix_allowance_one(mat[1], f.F_betax_um, v));
    f.F_betay_um = f.F_betax_um - f.y_beta_um;
    const double r = c.c_gamma_beta * f.F_betay_um / (2.0 * w_m);
    f.K_Hbeta = r <= 1.0 ? 1.0 + r : 2.0 * std::sqrt(r);
    f.K_Hbeta_from = F_betax_um > 0.0 ? "F_betax given" : "F_betax = 1.33 f_sh + f_ma";
  }
  // N_F from the smaller face width over tooth depth, not below 3.
  const double bh = std::max(3.0, g.spec.b / std::max(g.h[0], g.h[1]));
  f.N_F = bh * bh / (1.0 + bh + bh * bh);
  f.K_Fbeta = std::pow(f.K_Hbeta, f.N_F);
  return f;
}

TransverseLoadFactor transverse_load_factor(const PairGeometry& g, const MeshStiffness& c,
                                            double f_pb_um, double y_alpha_um, double F_tH,
                                            double Z_eps) {
  const double w = F_tH / (g.spec.b * kMm);
  const double dev = c.c_gamma_alpha * std::max(0.0, f_pb_um - y_alpha_um) / w;
  const double eg = g.eps_gamma;
  const double k =
      eg <= 2.0 ? 0.5 * eg * (0.9 + 0.4 * dev) : 0.9 + 0.4 * std::sqrt(2.0 * (eg - 1.0) / eg) * dev;
  TransverseLoadFactor t;
  t.K_Halpha = std::clamp(k, 1.0, std::max(1.0, eg / (g.eps_alpha * Z_eps * Z_eps)));
  t.K_Falpha = std::clamp(k, 1.0, std::max(1.0, eg / (0.25 * g.eps_alpha + 0.75)));
  return t;
}

}  // namespace gearsph::gear::iso6336
