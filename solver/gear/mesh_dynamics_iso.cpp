#include "solver/gear/mesh_dynamics_iso.hpp"

#include <array>
#include <numbers>

#include "solver/gear/iso6336_factors.hpp"
#include "solver/gear/iso6336_geometry.hpp"

namespace gearsph::gear::dynamics {

IsoDynamics iso_rack_pinion_dynamics(const geometry::PinionGeometry& pinion, double b,
                                     double E_pinion, double E_rack, double rho_pinion, double F_t,
                                     double n1_rpm) {
  namespace iso = iso6336;
  const geometry::BasicRack& tool = pinion.spec().tool;
  iso::PairSpec s;
  s.m_n = tool.module_m;
  s.alpha_n = tool.pressure_angle_rad;
  s.b = b;
  s.z = {pinion.teeth(), iso::kRackTeeth};
  s.x = {pinion.spec().profile_shift, 0.0};
  s.d_a = {2.0 * pinion.tip_radius(), 0.0};
  s.d_Nf = {2.0 * pinion.form_radius(), 0.0};
  s.rack = true;
  s.tool.h_aP = tool.addendum() / tool.module_m;
  s.tool.h_fP = tool.dedendum() / tool.module_m;
  s.tool.rho_fP = tool.root_radius() / tool.module_m;
  const iso::PairGeometry g = iso::pair_geometry(s);
  // A case-hardened class: with no deviation its running-in allowance is
  // zero (min(0.075 * 0, 3) um) and needs no sigma_Hlim; the class enters
  // method B's K_v nowhere else. The rack's density does not enter (its
  // mass is taken as infinite).
  std::array<iso::GearMaterial, 2> mat;
  mat[0].E_Pa = E_pinion;
  mat[1].E_Pa = E_rack;
  mat[0].rho_kg_m3 = mat[1].rho_kg_m3 = rho_pinion;
  mat[0].cls = mat[1].cls = iso::MaterialClass::Eh;
  const double w = F_t / (b * 1e3);  // N/mm
  const iso::MeshStiffness c = iso::mesh_stiffness(g, mat, w);
  const iso::Deviations dev;                                         // a perfect involute
  const double v = n1_rpm * std::numbers::pi / 30.0 * 0.5 * g.d[0];  // pitch-line speed
  const iso::DynamicFactor k = iso::dynamic_factor(g, mat, c, dev, n1_rpm, w, v);
  IsoDynamics out;
  out.c_prime_N_mm_um = c.c_prime;
  out.c_gamma_alpha_N_mm_um = c.c_gamma_alpha;
  out.m_red_kg_mm = k.m_red_kg_mm;
  out.n_E1_rpm = k.n_E1_rpm;
  out.resonance_mesh_Hz = k.n_E1_rpm * pinion.teeth() / 60.0;
  out.N = k.N;
  out.K_v = k.K_v;
  out.range = k.range;
  return out;
}

}  // namespace gearsph::gear::dynamics
