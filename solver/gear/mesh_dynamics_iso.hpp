#pragma once
// ISO 6336-1:2006 method B's view of a rack-and-pinion's dynamics, beside
// the lumped model (mesh_dynamics_sdof.hpp): the resonance speed n_E1 and
// the dynamic factor K_v of a pinion with its rack, from the existing
// rating code (iso6336_factors.hpp), for gears without deviations (the
// particles' perfect involutes: f_pb = f_falpha = 0, no tip relief).
#include <string>

#include "solver/geometry/gear_profile.hpp"

namespace gearsph::gear::dynamics {

struct IsoDynamics {
  double c_prime_N_mm_um = 0.0, c_gamma_alpha_N_mm_um = 0.0;
  // ISO 6336-1:2006, 6.5.9: for a rack the reduced mass is the pinion's
  // alone, pi rho d_m1^4 / (8 d_b1^2) per mm of face (the rack as a wheel
  // of infinite mass: iso6336_geometry.hpp's kRackTeeth makes its term
  // vanish).
  double m_red_kg_mm = 0.0;
  double n_E1_rpm = 0.0;
  double resonance_mesh_Hz = 0.0;  // n_E1 z_1 / 60
  double N = 0.0;                  // n_1 / n_E1
  double K_v = 1.0;
  std::string range;
};

// tangential_load_N: F_t (per gear) for ISO's line load F_t / b; n1_rpm
// the pinion's speed for N and K_v.
IsoDynamics iso_rack_pinion_dynamics(const geometry::PinionGeometry& pinion, double face_width_m,
                                     double E_pinion_Pa, double E_rack_Pa, double rho_pinion_kg_m3,
                                     double tangential_load_N, double n1_rpm);

}  // namespace gearsph::gear::dynamics
