#include "solver/geometry/mesh_placement.hpp"

#include <numbers>
#include <stdexcept>

namespace gearsph::geometry {

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

}  // namespace gearsph::geometry
