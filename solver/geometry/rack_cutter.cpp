#include "solver/geometry/rack_cutter.hpp"

#include <cmath>

namespace gearsph::geometry {

RackCutter::RackCutter(const BasicRack& profile, double pitch_radius, double shift, double backlash)
    : r_(pitch_radius),
      alpha_(profile.pressure_angle_rad),
      datum_(pitch_radius + shift * profile.module_m),
      half_space_(profile.pitch() / 4.0 - backlash / 2.0),
      rho_(profile.root_radius()) {
  // Round tangent to the tool tip line (depth h_fP below the datum) and to the
  // flank, inside the cutter tooth.
  const double yc = datum_ - profile.dedendum() + rho_;
  round_centre_ = {flank_x(yc) + rho_ / std::cos(alpha_), yc};
  // T lies r sin^2(alpha) below the rolling line; the flank point at height y
  // touches at ell = (y - y_T) / sin(alpha).
  const double y_tangent = yc - rho_ * std::sin(alpha_);
  const double y_t = r_ * std::cos(alpha_) * std::cos(alpha_);
  ell_round_ = (y_tangent - y_t) / std::sin(alpha_);
}

double RackCutter::flank_x(double y) const {
  return half_space_ - (y - datum_) * std::tan(alpha_);
}

double RackCutter::theta_flank() const {
  return std::numbers::pi + alpha_;
}

Point RackCutter::envelope(Point c, Point n) const {
  const double s = -c.x - (r_ - c.y) * n.x / n.y;
  return rotate({c.x + s, c.y}, s / r_);
}

Point RackCutter::fillet_point(double theta) const {
  const Point n{std::cos(theta), std::sin(theta)};
  return envelope(round_centre_ + rho_ * n, n);
}

Point RackCutter::flank_point(double ell) const {
  const double y = r_ * std::cos(alpha_) * std::cos(alpha_) + ell * std::sin(alpha_);
  return envelope({flank_x(y), y}, {std::cos(alpha_), std::sin(alpha_)});
}

}  // namespace gearsph::geometry
