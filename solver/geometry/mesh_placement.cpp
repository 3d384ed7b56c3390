#include "solver/geometry/mesh_placement.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace gearsph::geometry {

double tip_reach_below_datum(const PinionGeometry& pinion) {
  const BasicRack& t = pinion.spec().tool;
  return pinion.tip_radius() - pinion.pitch_radius() - pinion.spec().profile_shift * t.module_m;
}

MatingRackShape mating_rack_shape(const PinionGeometry& pinion, int rack_teeth) {
  constexpr double kClearanceModules = 0.05;
  const BasicRack& tool = pinion.spec().tool;
  const double clearance = kClearanceModules * tool.module_m;
  MatingRackShape shape{tool, 0.0};
  shape.profile.root_radius_coef =
      tool.root_radius_clearing(tip_reach_below_datum(pinion), clearance) / tool.module_m;
  if (rack_teeth > 1) {
    shape.tip_radius_coef =
        tool.tip_radius_clearing(tool.straight_flank_depth(), clearance) / tool.module_m;
  }
  return shape;
}

MeshPlacement place_in_mesh(const PinionGeometry& pinion, const RackGeometry& rack,
                            Point pinion_centre, int pinion_tooth, int rack_space,
                            double travel_m) {
  const BasicRack& pt = pinion.spec().tool;
  const BasicRack& rt = rack.spec().profile;
  if (pt.module_m != rt.module_m || pt.pressure_angle_rad != rt.pressure_angle_rad) {
    throw std::invalid_argument("rack and pinion need the same module and pressure angle");
  }
  const double r = pinion.pitch_radius();
  MeshPlacement out;
  out.centre_distance = r + pinion.spec().profile_shift * pt.module_m;
  out.rolling_line_y = pinion_centre.y - r;
  const double turn = travel_m / r;
  out.pinion.angle = -std::numbers::pi / 2.0 - pinion.tooth_centre_angle(pinion_tooth) + turn;
  out.pinion.shift = pinion_centre;
  out.rack.angle = 0.0;
  out.rack.shift = {pinion_centre.x + travel_m - rack.space_centre_x(rack_space),
                    pinion_centre.y - out.centre_distance};
  return out;
}

double travel_for_contact(const PinionGeometry& pinion, int pinion_tooth, double radius,
                          double phase, bool clockwise) {
  const double rb = pinion.base_radius(), r = pinion.pitch_radius();
  if (!(radius > rb && radius <= pinion.tip_radius() * (1.0 + 1e-12))) {
    throw std::invalid_argument("contact radius must lie between the base and the tip circle");
  }
  const double alpha = pinion.spec().tool.pressure_angle_rad;
  // Clockwise drive (the mirror image gives the other): T at the lower right
  // of the centre, the line of action through the pitch point P = (0, -r) at
  // alpha, contact points Q(g) = T - g (cos alpha, sin alpha).
  const Point T{r * std::sin(alpha) * std::cos(alpha), -r * std::cos(alpha) * std::cos(alpha)};
  const double g = std::sqrt(radius * radius - rb * rb);
  const Point Q = T - g * Point{std::cos(alpha), std::sin(alpha)};
  // Tooth k's axis at -pi/2 + 2 pi k / z + turn, its leading (driving) flank
  // psi further clockwise; mirror: the tooth -k of the mirrored pinion.
  const double psi = pinion.involute_half_angle(radius);
  const int k = clockwise ? pinion_tooth : -pinion_tooth;
  const double axis =
      -std::numbers::pi / 2.0 + pinion.tooth_centre_angle(k) - pinion.tooth_centre_angle(0);
  const double mirrored_phase = clockwise ? phase : -phase;
  const double turn =
      std::remainder(std::atan2(Q.y, Q.x) + psi - axis, 2.0 * std::numbers::pi) - mirrored_phase;
  return (clockwise ? 1.0 : -1.0) * r * turn;  // rolling: the pinion turns travel / r
}

}  // namespace gearsph::geometry
