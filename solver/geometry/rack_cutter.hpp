#pragma once
// The rack-type cutter that generates the pinion, and the envelope of its
// profile as it rolls without slip on the pitch circle (generating or
// "hobbing" kinematics; Litvin & Fuentes, Gear Geometry and Applied Theory,
// 2nd ed. 2004, ch. 6 and 11).
//
// Generating frame: gear centre at the origin, the tooth being cut centred on
// the +y axis, the cutter above it with its teeth pointing down. The cutter's
// datum line is y = r + x m (profile shift x moves the tool away from the
// centre), its rolling line y = r touches the pitch circle at the pitch point
// I = (0, r). The cutter space centred on x = 0 forms the tooth; the cutter
// tooth centred on x = p/2 forms the tooth's right flank (x > 0) with its left
// flank and its tip round. The backlash allowance j_t widens each cutter tooth
// by j_t/2 per flank at the datum line, so the cut tooth is thinner by j_t/2
// per flank at the pitch circle while the root circle stays where it is.
//
// Envelope (law of meshing): a cutter point with profile normal n touches the
// gear when that normal passes through I. For cutter displacement s along +x
// the gear has turned by s / r clockwise, so in the gear frame the contact
// point is R(s / r) (c + (s, 0)) with s = -c_x - (r - c_y) n_x / n_y.
#include "solver/geometry/basic_rack.hpp"
#include "solver/geometry/polygon.hpp"

namespace gearsph::geometry {

class RackCutter {
 public:
  RackCutter(const BasicRack& profile, double pitch_radius, double shift, double backlash);

  // Gear point cut by the tip round where its outward normal has angle theta,
  // theta in [theta_flank(), 3 pi / 2]; 3 pi / 2 touches the root circle.
  Point fillet_point(double theta) const;
  double theta_flank() const;  // pi + alpha: where the round meets the flank

  // Gear point cut by the straight flank whose contact lies on the line of
  // action at signed distance ell from its tangency T with the base circle
  // (ell > 0 towards I): the involute, |point| = sqrt(r_b^2 + ell^2). Points
  // with ell < 0 form the involute's second branch, which only exists as part
  // of an undercut and is never on the finished tooth.
  Point flank_point(double ell) const;
  // ell of the flank point where the straight flank meets the tip round;
  // negative means the tooth is undercut (the flank reaches below T).
  double ell_round() const { return ell_round_; }

  // Half angle (from the tooth axis) where the fillet leaves the root circle.
  double root_half_angle() const { return round_centre_.x / r_; }

 private:
  Point envelope(Point c, Point n) const;
  double flank_x(double y) const;  // abscissa of the straight cutter flank at height y

  double r_;            // pitch radius
  double alpha_;        // pressure angle
  double datum_;        // y of the cutter datum line, r + x m
  double half_space_;   // half the cutter space width at the datum line
  double rho_;          // tip round radius
  Point round_centre_;  // tip round centre at s = 0
  double ell_round_;
};

}  // namespace gearsph::geometry
