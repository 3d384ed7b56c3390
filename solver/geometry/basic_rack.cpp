#include "solver/geometry/basic_rack.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace gearsph::geometry {

double BasicRack::straight_flank_depth() const {
  return dedendum() - root_radius() * (1.0 - std::sin(pressure_angle_rad));
}

// The straight flank ends at h_fP - rho (1 - sin alpha): solve for rho.
double BasicRack::root_radius_clearing(double reach, double clearance) const {
  const double largest = (dedendum() - reach - clearance) / (1.0 - std::sin(pressure_angle_rad));
  return std::clamp(largest, 0.0, root_radius());
}

// A tip round of radius rho ends the flank at h_aP - rho (1 - sin alpha).
double BasicRack::tip_radius_clearing(double form, double clearance) const {
  return std::max(0.0, (addendum() - form + clearance) / (1.0 - std::sin(pressure_angle_rad)));
}

// Fillet centre at depth h_fP - rho on the space side of the flank; it reaches
// the space centre line when (p/4 + w/2) - (h_fP - rho) tan(alpha) = rho / cos(alpha).
double BasicRack::max_root_radius(double widening) const {
  const double a = pressure_angle_rad;
  const double half_space_at_root = pitch() / 4.0 + widening / 2.0 - dedendum() * std::tan(a);
  return half_space_at_root * std::cos(a) / (1.0 - std::sin(a));
}

double BasicRack::default_root_radius_coef(double widening) const {
  constexpr double kIso53A = 0.38;
  // Nine tenths of the largest: the two fillets of a space then leave a root
  // land between them. At the largest they meet in a point of the outline
  // (the FE check's mesher made an inverted element there).
  constexpr double kOfLargest = 0.9;
  return std::min(kIso53A, kOfLargest * max_root_radius(widening) / module_m);
}

void BasicRack::validate(double widening) const {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("basic rack profile: " + what);
  };
  if (!(module_m > 0.0)) fail("module must be positive");
  if (!(pressure_angle_rad > 0.0 && pressure_angle_rad < std::numbers::pi / 4.0)) {
    fail("pressure angle must lie in (0, 45) degrees");
  }
  if (!(addendum_coef > 0.0)) fail("addendum coefficient must be positive");
  if (!(dedendum_coef >= addendum_coef)) fail("dedendum must not be shorter than the addendum");
  if (!(root_radius_coef >= 0.0)) fail("root fillet radius must not be negative");
  if (root_radius() > max_root_radius(widening)) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "the cutter's tip radius coefficient rho_fP* %.3f does not fit the tooth space "
                  "(the largest, where the two fillets meet, is %.3f)",
                  root_radius_coef, max_root_radius(widening) / module_m);
    fail(text);
  }
  if (straight_flank_depth() <= -addendum()) fail("fillets leave no straight flank");
}

}  // namespace gearsph::geometry
