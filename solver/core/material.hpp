#pragma once
// Linear elastic material of one body (plane strain, SI units).
#include <cmath>
#include <string>

namespace gearsph {

struct Material {
  double E = 0.0;     // Young's modulus [Pa]
  double nu = 0.0;    // Poisson's ratio [-]
  double rho0 = 0.0;  // reference density [kg/m^3]

  double bulk_modulus() const { return E / (3.0 * (1.0 - 2.0 * nu)); }
  double shear_modulus() const { return E / (2.0 * (1.0 + nu)); }
  double lame_lambda() const { return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)); }
  // P-wave modulus K + 4G/3: the stiffness of laterally confined (1D strain) compression.
  double p_wave_modulus() const { return bulk_modulus() + 4.0 * shear_modulus() / 3.0; }
  // The fastest signal in the solid; it sets the Courant time step (method.md).
  double p_wave_speed() const { return std::sqrt(p_wave_modulus() / rho0); }
  double bulk_sound_speed() const { return std::sqrt(bulk_modulus() / rho0); }
  // Longitudinal speed in a thin plane-strain strip (free lateral faces).
  double strip_wave_speed() const { return std::sqrt(E / (rho0 * (1.0 - nu * nu))); }
};

}  // namespace gearsph
