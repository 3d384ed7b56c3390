#pragma once
// The rack-and-pinion scene (method.md, "The paper's gear case"): what the
// builder decided, shared with the analysis of the finished run.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/gear/gear_rating.hpp"
#include "solver/run/history.hpp"

namespace gearsph {
struct Simulation;
}

namespace gearsph::scenes {

struct GearLayout {
  // Pinion.
  int teeth = 12;
  double module_m = 4e-3, pressure_angle = 0.349, face_width_m = 0.02;
  double pitch_radius = 0, base_radius = 0, tip_radius = 0, root_radius = 0, form_radius = 0;
  double cx = 0, cy = 0;            // pinion centre [m]
  double omega = -15.0;             // [rad/s], counter-clockwise positive; initial if torque-driven
  std::optional<double> torque_Nm;  // per gear, counter-clockwise positive: the hub is driven by it
  std::vector<int> pinion_teeth;    // modelled teeth, numbered from the one in mesh at t = 0
  // Rack.
  double rack_velocity = -0.353;  // initial [m/s]
  double load_N = 0.0;            // resisting force, per gear
  std::vector<int> rack_teeth;    // modelled rack teeth, numbered from the first
  double end_s = 0.04;
  gear::ContactPath path;
  gear::IsoToothForm iso_tip, iso_hpstc, iso_pitch;
  double lewis_Y = 0.0;
  double iso_mesh_stiffness = 0.0;  // c' [N/m per m of face width], ISO 6336-1
  // The largest contact force an elastic mesh can see from the start: the
  // load plus the impact of the initial mismatch of pitch-line speeds on the
  // mesh spring, dv sqrt(k m_rack) (per gear) [N].
  double impact_force_bound_N = 0.0;
  bool quasi_static = false;
  // ISO 6336-3 critical section of tooth 0 (between its 30-degree points):
  // the lattice row that lies on it, for the section's bending moment.
  struct Section {
    std::vector<std::size_t> particles;
    double cx = 0, cy = 0;  // chord centre [m]
    double ux = 1, uy = 0;  // along the chord
    double width = 0;       // s_Fn [m]
    double dx = 0;
  } root_section;
  std::vector<Section> tooth_sections;  // the same for every modelled tooth, in pinion_teeth order
  std::vector<std::size_t> tooth0_particles;
  std::vector<gear::IsoToothForm> iso_by_radius;  // form radius to tip, ascending
  std::string selection;                          // how the modelled teeth were chosen, in words
};

// Velocity-stability time (docs/gears.md): the earliest t* after which v(t)
// stays within +/- tolerance of its mean over [t*, end]. -1 if never (the
// signal is still varying at the end); 0 if always.
double velocity_stability_time(const std::vector<double>& t, const std::vector<double>& v,
                               double tolerance);

// Normal force and bending moment on a tooth's root section, from the
// normal stress of the particles on it, with the section turned by the
// hub's angle about the pinion centre (cx, cy): 6 |M| / s^2 is the nominal
// bending stress that ISO 6336-3's Y_F describes.
struct SectionLoads {
  double normal_force = 0.0;    // [N/m]
  double bending_moment = 0.0;  // [N m / m]
  double nominal_bending_stress = 0.0;
};
SectionLoads section_loads(const GearLayout::Section& sec, const Simulation& sim, double angle,
                           double cx, double cy);

nlohmann::json analyse_rack_pinion(const GearLayout& layout, const History& h,
                                   const Simulation& final_state);

}  // namespace gearsph::scenes
