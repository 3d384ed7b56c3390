#pragma once
// A segment of the mating rack: n teeth of the ISO 53 basic rack profile
// (basic_rack.hpp) on a rectangular body.
//
// Rack frame: datum line y = 0, teeth pointing +y (towards a pinion above),
// tooth j centred at x = j p (j = 0 .. n - 1), tips at y = h_aP, root line at
// y = -h_fP, straight root fillets of radius rho_fP, back face at
// y = -h_fP - back_thickness. The segment ends on the space centres at
// x = -p/2 and x = (n - 1/2) p. Outline CCW.
//
// The backlash allowance j thins each tooth by j/2 per flank at the datum
// line; a pinion with allowance j_t meshing with it at the nominal centre
// distance then has j + j_t of play along the pitch line.
#include <vector>

#include "solver/geometry/basic_rack.hpp"
#include "solver/geometry/polygon.hpp"

namespace gearsph::geometry {

struct RackSpec {
  BasicRack profile;
  int teeth = 5;
  double back_thickness_m = 8e-3;  // body below the root line (2 m in the seed paper's case)
  double backlash_m = 0.0;         // total thinning at the datum line
  double tip_radius_coef = 0.0;    // optional rounding of the tip corners (not in ISO 53)
  double chord_tolerance_m = 1e-7;
};

class RackGeometry {
 public:
  explicit RackGeometry(const RackSpec& spec);  // throws std::invalid_argument

  const RackSpec& spec() const { return spec_; }
  int teeth() const { return spec_.teeth; }
  double pitch() const { return spec_.profile.pitch(); }
  // Tooth thickness at the datum line: p/2 - j.
  double datum_thickness() const { return pitch() / 2.0 - spec_.backlash_m; }
  double tip_y() const { return spec_.profile.addendum(); }
  double root_y() const { return -spec_.profile.dedendum(); }
  double back_y() const { return root_y() - spec_.back_thickness_m; }
  double tooth_centre_x(int j) const { return pitch() * j; }
  // Abscissa of the space centre between teeth i - 1 and i, (i - 1/2) p.
  double space_centre_x(int i) const { return pitch() * (i - 0.5); }

  // Right half of tooth 0 (x >= 0), from the space centre on the root line to
  // the end of the tip line at the axis (excluded), in traversal order.
  const std::vector<Point>& half_tooth() const { return half_; }
  const Polygon& outline() const { return outline_; }

 private:
  void validate() const;
  void build_half_tooth();
  void build_outline();
  double flank_x(double y) const;  // right flank abscissa at height y

  RackSpec spec_;
  std::vector<Point> half_;
  Polygon outline_;
};

}  // namespace gearsph::geometry
