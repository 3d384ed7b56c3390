#pragma once
// The rack-and-pinion scene (method.md, "The paper's gear case"): what the
// builder decided, shared with the analysis of the finished run.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/gear/gear_rating.hpp"
#include "solver/run/history.hpp"

namespace gearsph::scenes {

struct GearLayout {
  // Pinion.
  int teeth = 12;
  double module_m = 4e-3, pressure_angle = 0.349, face_width_m = 0.02;
  double pitch_radius = 0, base_radius = 0, tip_radius = 0, root_radius = 0, form_radius = 0;
  double cx = 0, cy = 0;          // pinion centre [m]
  double omega = -15.0;           // [rad/s], counter-clockwise positive
  std::vector<int> pinion_teeth;  // modelled teeth, numbered from the one in mesh at t = 0
  // Rack.
  double rack_velocity = -0.353;  // initial [m/s]
  double load_N = 0.0;            // resisting force, per gear
  std::vector<int> rack_teeth;    // modelled rack teeth, numbered from the first
  double end_s = 0.04;
  gear::ContactPath path;
  gear::IsoToothForm iso_tip, iso_hpstc;
  double lewis_Y = 0.0;
  std::string selection;  // how the modelled teeth were chosen, in words
};

// Velocity-stability time (docs/gears.md): the earliest t* after which v(t)
// stays within +/- tolerance of its mean over [t*, end]. -1 if never (the
// signal is still varying at the end); 0 if always.
double velocity_stability_time(const std::vector<double>& t, const std::vector<double>& v,
                               double tolerance);

nlohmann::json analyse_rack_pinion(const GearLayout& layout, const History& h);

}  // namespace gearsph::scenes
