#pragma once
// ISO 6336-2:2006 surface durability (pitting), method B: the contact stress
// sigma_H at the pitch point (or at the inner points of single contact) and
// the influence factors on the permissible contact stress.
#include <array>

#include "solver/gear/iso6336_geometry.hpp"
#include "solver/gear/iso6336_materials.hpp"

namespace gearsph::gear::iso6336 {

// Zone factor, clause 6: Z_H = sqrt(2 cos b_b cos a_wt / (cos^2 a_t sin a_wt)).
double zone_factor(const PairGeometry& g);
// Elasticity factor, clause 7 [sqrt(Pa)]: sqrt(1 / (pi sum (1 - nu^2)/E)).
double elasticity_factor(const GearMaterial& m1, const GearMaterial& m2);
// Contact ratio factor, clause 8.
double contact_ratio_factor(const PairGeometry& g);
// Helix angle factor, clause 9 (the 2006 edition): 1/sqrt(cos beta).
double helix_angle_factor(const PairGeometry& g);

// Single pair tooth contact factors Z_B (pinion) and Z_D (wheel), clause
// 6.2: the contact stress at the inner point of single contact over that
// at the pitch point, for spur gears; 1 for eps_beta >= 1; between.
std::array<double, 2> single_pair_factors(const PairGeometry& g);

// Lubricant, velocity and roughness factors, clause 11 (method B), for the
// pair's lower sigma_Hlim. nu40 in mm^2/s, v in m/s, Rz in um.
double lubricant_factor(double sigma_Hlim_Pa, double nu40_mm2_s);
double velocity_factor(double sigma_Hlim_Pa, double v_m_s);
double roughness_factor(double sigma_Hlim_Pa, double Rz1_um, double Rz2_um, double rho_red_m);

// Work hardening factor, clause 12: raises the permissible stress of a
// through-hardened gear that runs against a surface-hardened, smooth one
// (Z_W = (1.2 - (HB - 130)/1700) (3/R_zH)^0.15); 1 otherwise.
std::array<double, 2> work_hardening_factors(const PairGeometry& g,
                                             const std::array<GearMaterial, 2>& mat,
                                             const std::array<double, 2>& Rz_um, double nu40_mm2_s,
                                             double v_m_s);

// Nominal contact stress at the pitch point, clause 5: F_t the nominal
// tangential force at the reference circle. A rack: (u + 1)/u = 1.
double nominal_contact_stress(const PairGeometry& g, double F_t_N, double Z_H, double Z_E,
                              double Z_eps, double Z_beta);

}  // namespace gearsph::gear::iso6336
