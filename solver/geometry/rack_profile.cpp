#include "solver/geometry/rack_profile.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "solver/geometry/curve_sampling.hpp"

namespace gearsph::geometry {

RackGeometry::RackGeometry(const RackSpec& spec) : spec_(spec) {
  validate();
  build_half_tooth();
  build_outline();
}

void RackGeometry::validate() const {
  auto fail = [](const std::string& what) { throw std::invalid_argument("rack: " + what); };
  if (spec_.teeth < 1) fail("needs at least one tooth");
  if (!(spec_.back_thickness_m > 0.0)) fail("back thickness must be positive");
  if (!(spec_.backlash_m >= 0.0)) fail("backlash allowance must not be negative");
  if (!(spec_.chord_tolerance_m > 0.0)) fail("chord tolerance must be positive");
  spec_.profile.validate(spec_.backlash_m);
  const double tip_half = flank_x(tip_y());
  const double a = spec_.profile.pressure_angle_rad;
  // A tip round of radius rho fits when its centre stays on the tooth's side
  // of the axis: rho (1 - sin a) / cos a <= half tip width.
  const double rho_tip = spec_.tip_radius_coef * spec_.profile.module_m;
  if (!(rho_tip >= 0.0)) fail("tip radius must not be negative");
  if (rho_tip * (1.0 - std::sin(a)) / std::cos(a) > tip_half) fail("tip radius does not fit");
  if (!(tip_half > 0.0)) fail("pointed tooth");
  // The flank must keep a straight piece between the two rounds.
  const double tip_round_foot = tip_y() - rho_tip * (1.0 - std::sin(a));
  if (!(tip_round_foot > -spec_.profile.straight_flank_depth())) {
    fail("tip and root rounds leave no straight flank");
  }
}

double RackGeometry::flank_x(double y) const {
  return datum_thickness() / 2.0 - y * std::tan(spec_.profile.pressure_angle_rad);
}

// Right half: root line, root fillet, flank, tip round, tip line.
void RackGeometry::build_half_tooth() {
  const double a = spec_.profile.pressure_angle_rad, tol = spec_.chord_tolerance_m;
  const double rho = spec_.profile.root_radius();
  const double rho_tip = spec_.tip_radius_coef * spec_.profile.module_m;
  const Point normal{std::cos(a), std::sin(a)};  // flank normal, out of the tooth
  half_.clear();
  half_.push_back({space_centre_x(1), root_y()});
  // Root fillet: centre in the space, tangent to the root line and the flank.
  const double yc = root_y() + rho;
  const Point root_centre{flank_x(yc) + rho / std::cos(a), yc};
  if (rho > 0.0) {
    auto fillet = [&](double phi) {
      return root_centre + rho * Point{std::cos(phi), std::sin(phi)};
    };
    sample_curve(fillet, -std::numbers::pi / 2.0, a - std::numbers::pi, tol, half_);
  }
  half_.push_back(root_centre - rho * normal);
  // Tip round: centre inside the tooth, tangent to the flank and the tip line.
  const double yt = tip_y() - rho_tip;
  const Point tip_centre{flank_x(yt) - rho_tip / std::cos(a), yt};
  if (rho_tip > 0.0) {
    auto round = [&](double phi) {
      return tip_centre + rho_tip * Point{std::cos(phi), std::sin(phi)};
    };
    sample_curve(round, a, std::numbers::pi / 2.0, tol, half_);
  }
  half_.push_back({tip_centre.x, tip_y()});
}

// Bottom left, bottom right, then the teeth from right to left; the space
// centres are computed once each, so the ring has no near-duplicate vertices.
void RackGeometry::build_outline() {
  const int n = spec_.teeth;
  outline_.clear();
  outline_.push_back({space_centre_x(0), back_y()});
  outline_.push_back({space_centre_x(n), back_y()});
  for (int j = n - 1; j >= 0; --j) {
    const double cx = tooth_centre_x(j);
    outline_.push_back({space_centre_x(j + 1), root_y()});
    for (std::size_t i = 1; i < half_.size(); ++i)
      outline_.push_back({cx + half_[i].x, half_[i].y});
    for (std::size_t i = half_.size() - 1; i >= 1; --i) {
      outline_.push_back({cx - half_[i].x, half_[i].y});
    }
  }
  outline_.push_back({space_centre_x(0), root_y()});
}

}  // namespace gearsph::geometry
