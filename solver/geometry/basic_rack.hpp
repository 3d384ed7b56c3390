#pragma once
// The standard basic rack tooth profile, ISO 53:1998 (profile A by default):
// straight flanks at the pressure angle, addendum h_aP = 1.0 m above the datum
// line, dedendum h_fP = 1.25 m below it, root fillet radius rho_fP = 0.38 m,
// tooth thickness p/2 at the datum line. All proportions are settable
// (coefficients in units of the module).
//
// The same profile serves twice: the mating rack of the simulation has exactly
// this shape, and the rack-type cutter that generates the pinion is this
// profile with its tooth lengthened to h_fP and tipped with the radius rho_fP
// (the tool cuts the gear's dedendum and rounds its root fillet).
#include <numbers>

namespace gearsph::geometry {

struct BasicRack {
  double module_m = 4e-3;
  double pressure_angle_rad = 20.0 * std::numbers::pi / 180.0;
  double addendum_coef = 1.0;      // h_aP*
  double dedendum_coef = 1.25;     // h_fP*
  double root_radius_coef = 0.38;  // rho_fP*

  double pitch() const { return std::numbers::pi * module_m; }
  double addendum() const { return addendum_coef * module_m; }
  double dedendum() const { return dedendum_coef * module_m; }
  double root_radius() const { return root_radius_coef * module_m; }
  // Depth below the datum line where the straight flank meets the root
  // fillet: h_fP - rho_fP (1 - sin alpha) (= 0.99996 m for ISO 53 A, which is
  // why the standard undercut limit is quoted with h_aP).
  double straight_flank_depth() const;
  // Largest root fillet that fits a space whose width at the datum line is
  // p/2 + widening: the two fillets of one space meet on its centre line.
  double max_root_radius(double widening) const;
  // The tip radius coefficient a job gets when it gives none: ISO 53 profile
  // A's 0.38, or nine tenths of the largest that fits where that does not
  // (a 25-degree pressure angle at the standard depths: 0.29).
  double default_root_radius_coef(double widening) const;
  // The mating rack's root fillet radius [m] that keeps its straight flank
  // at least `clearance` [m] below the depth `reach` [m] a pinion's tip
  // enters below the datum line: the profile's own where that clears, else
  // the largest that does (0 at most: a sharp root corner).
  double root_radius_clearing(double reach, double clearance) const;
  // The mating rack's tip round radius [m] that ends its straight flank at
  // least `clearance` [m] below the height `form` [m] above the datum line
  // where the pinion's involute begins (its cutter's straight_flank_depth):
  // 0 where a sharp tip already clears.
  double tip_radius_clearing(double form, double clearance) const;
  // Throws std::invalid_argument naming the first bad value.
  void validate(double widening) const;
};

}  // namespace gearsph::geometry
