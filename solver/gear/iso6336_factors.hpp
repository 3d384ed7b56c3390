#pragma once
// ISO 6336-1:2006 load factors, method B: the mesh stiffness c' and
// c_gamma, the dynamic factor K_v from the resonance ratio, the face load
// factors K_Hbeta (from the effective equivalent misalignment) and K_Fbeta,
// and the transverse load factors K_Halpha and K_Falpha. ISO's empirical
// formulas are in its units, named in the fields: mm, um, N/mm, N/(mm um).
#include <array>
#include <string>

#include "solver/gear/iso6336_geometry.hpp"
#include "solver/gear/iso6336_materials.hpp"

namespace gearsph::gear::iso6336 {

// ISO 1328-1:2013 tolerances of one gear of an accuracy grade [um]:
// single pitch f_pT, profile form f_falphaT and helix slope f_HbetaT, each
// from its formula at grade 5 times sqrt(2) per grade.
struct GradeTolerances {
  double f_pt_um = 0.0, f_falpha_um = 0.0, f_Hbeta_um = 0.0;
};
GradeTolerances grade_tolerances(int grade, double m_n_mm, double d_mm, double b_mm);

// Theoretical single stiffness c'_th = 1/q' [N/(mm um)], ISO 6336-1:2006
// method B (q' of its Table 9), for virtual numbers of teeth z_n1, z_n2 (a rack: 1/z_n2 = 0).
double theoretical_single_stiffness(double z_n1, double inv_z_n2, double x1, double x2);
// Basic rack factor C_B (ISO 6336-1:2006, method B): dedendum h_fP* and pressure angle [rad].
double basic_rack_factor(double h_fP, double alpha_n);
// ISO's C_M: measured over theoretical stiffness of solid gears.
inline constexpr double kStiffnessCorrection = 0.8;
// E_st: the modulus ISO's stiffness data were measured on.
inline constexpr double kSteelModulusPa = 206e9;

struct MeshStiffness {
  double q_prime = 0.0, c_th = 0.0, C_B = 0.0, E_ratio = 1.0, load_correction = 1.0;
  double c_prime = 0.0, c_gamma_alpha = 0.0, c_gamma_beta = 0.0;  // N/(mm um)
};
// line_load_N_mm = F_t K_A / b.
MeshStiffness mesh_stiffness(const PairGeometry& g, const std::array<GearMaterial, 2>& mat,
                             double line_load_N_mm);

struct Deviations {
  double f_pb_um = 0.0, f_falpha_um = 0.0;  // larger of the two gears
  double C_a_um = 0.0;                      // tip relief
  std::array<double, 2> f_Hbeta_um{};       // helix slope deviation of each gear
};

struct DynamicFactor {
  double m_red_kg_mm = 0.0, n_E1_rpm = 0.0, N = 0.0, N_S = 0.0;
  double y_alpha_um = 0.0, y_f_um = 0.0, B_p = 0.0, B_f = 0.0, B_k = 0.0;
  double K_v = 1.0;
  std::string range;  // subcritical, main resonance, intermediate, supercritical
};
DynamicFactor dynamic_factor(const PairGeometry& g, const std::array<GearMaterial, 2>& mat,
                             const MeshStiffness& c, const Deviations& dev, double n1_rpm,
                             double line_load_N_mm, double v_m_s);

struct FaceLoadFactor {
  double f_sh_um = 0.0, f_ma_um = 0.0, F_betax_um = 0.0, y_beta_um = 0.0, F_betay_um = 0.0;
  double K_Hbeta = 1.0, N_F = 0.0, K_Fbeta = 1.0;
  std::string K_Hbeta_from;
};
// K_Hbeta from the effective equivalent misalignment F_betay (ISO 6336-1:2006,
// method C of clause 7), F_betax given (> 0) or 1.33 f_sh + f_ma with f_sh
// of a stiff pinion shaft (K' = 0) and f_ma from the helix slope deviations;
// or K_Hbeta_given (> 0) as it stands. K_Fbeta = K_Hbeta^N_F (method B).
FaceLoadFactor face_load_factor(const PairGeometry& g, const std::array<GearMaterial, 2>& mat,
                                const MeshStiffness& c, const Deviations& dev, double F_m_N,
                                double v_m_s, double F_betax_um, double K_Hbeta_given);

struct TransverseLoadFactor {
  double K_Halpha = 1.0, K_Falpha = 1.0;
};
// Method B of ISO 6336-1:2006 clause 8, F_tH = F_t K_A K_v K_Hbeta; Z_eps
// bounds K_Halpha.
TransverseLoadFactor transverse_load_factor(const PairGeometry& g, const MeshStiffness& c,
                                            double f_pb_um, double y_alpha_um, double F_tH_N,
                                            double Z_eps);

// Running-in allowance y_alpha of a pitch or profile deviation of the pair
// (ISO 6336-1:2006, clause 8): the mean of the two gears' allowances.
double running_in_allowance(const std::array<GearMaterial, 2>& mat, double deviation_um,
                            double v_m_s);

}  // namespace gearsph::gear::iso6336
