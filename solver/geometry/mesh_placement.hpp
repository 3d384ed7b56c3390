#pragma once
// Puts a pinion (gear frame, gear_profile.hpp) and a rack (rack frame,
// rack_profile.hpp) into one world frame, rack below the pinion, in mesh.
//
// Geometry of a rack and pinion pair (ISO 21771:2007; the rack is never
// shifted): the rack's datum line sits at the centre distance a = r + x m
// below the pinion centre, the same place as the datum line of the cutter
// that generated the pinion. The rolling (operating pitch) line of the rack is
// the line tangent to the pinion's pitch circle, r below the centre, i.e. x m
// below the rack datum; the working pressure angle is alpha for any shift.
// Rolling without slip: a rack displacement d along +x turns the pinion by
// d / r counter-clockwise (the seed paper's clockwise pinion drives the rack -x).
//
// Phase: at travel 0, pinion tooth k points straight down (-y) and sits in the
// rack space i, centred between rack teeth i - 1 and i. This is the position
// in which the cutter cut that tooth, so without backlash allowances both of
// its flanks touch the rack; with allowances the play is shared equally.
#include "solver/geometry/gear_profile.hpp"
#include "solver/geometry/polygon.hpp"
#include "solver/geometry/rack_profile.hpp"

namespace gearsph::geometry {

struct MeshPlacement {
  Transform pinion;              // gear frame -> world
  Transform rack;                // rack frame -> world
  double centre_distance = 0.0;  // pinion centre to rack datum line, r + x m
  double rolling_line_y = 0.0;   // world y of the rack's rolling line
};

// The depth below the rack's datum line that the pinion's tip circle
// reaches in mesh: r_a - (r + x m) (h_aP = 1.0 m for a standard tip at any
// shift).
double tip_reach_below_datum(const PinionGeometry& pinion);

// The mating rack as modelled, in static checks, dynamic runs and the FE
// check alike: the pinion's tool, with two clearances of a twentieth of a
// module each where the rack's straight flank would otherwise end on the
// pinion's and a corner would bear on a flank.
// - Root: the fillet kept below the pinion tip's reach. ISO 53 A's straight
//   flank ends 4e-5 m above a standard tip's reach (h_fP - rho_fP (1 - sin
//   alpha) = 0.99996 m at 20 degrees) and above it at smaller pressure
//   angles, so the tip corner met the rack's root fillet where it meets the
//   flank: its force turned radial and put tooth 0's load 26 % above the
//   rack's at the tip (docs/validation.md, "Wedged racks").
// - Tip: rounded so that its straight flank ends below the pinion's form
//   circle, which the cutter's flank end generated at the same 0.99996 m: a
//   sharp rack tip reaches it, and its corner jammed in the pinion's fillet
//   as the tooth came into mesh (docs/validation.md, "The rack's tip").
//   A rack of one tooth (a static check's, and its FE check's) keeps the
//   tool's sharp tip: its driving flank bears on tooth 0 and its reverse
//   flank touches nothing (rack_contact_side), so its tip meets no fillet,
//   and the round would only move its outline's particles (the static
//   check's mesh stiffness read 1.2 % lower with it).
// 0.05 m keeps the flank particle at either end off the round at the
// default spacings (a flank spacing is 0.1-0.2 m).
struct MatingRackShape {
  BasicRack profile;           // the tool's, its root radius cleared
  double tip_radius_coef = 0;  // RackSpec::tip_radius_coef
};
MatingRackShape mating_rack_shape(const PinionGeometry& pinion, int rack_teeth);

MeshPlacement place_in_mesh(const PinionGeometry& pinion, const RackGeometry& rack,
                            Point pinion_centre, int pinion_tooth, int rack_space,
                            double travel_m = 0.0);

// The rack travel at which tooth k's driving flank touches the rack at
// `radius` on the pinion (r_b < radius <= r_a), with the pinion turned
// besides by `phase` (counter-clockwise, e.g. to close the play on the
// driving side). The driving flank of a clockwise pinion is the one that
// leads as it turns (for tooth 0, pointing down, the flank facing -x); a
// counter-clockwise one is its mirror image.
//
// The contact lies on the line of action, tangent to the base circle at T,
// at g = sqrt(radius^2 - r_b^2) from T; the flank point at that radius sits
// the involute half angle psi(radius) from the tooth axis (gear_profile.hpp).
// The tooth is in contact there when that flank point and the point g of the
// line of action have the same polar angle.
double travel_for_contact(const PinionGeometry& pinion, int pinion_tooth, double radius,
                          double phase, bool clockwise);

}  // namespace gearsph::geometry
