#pragma once
// The rack-and-pinion scene (method.md, "The seed paper's gear case"): what the
// builder decided, shared with its history columns and the analysis of the
// finished run.
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/diagnostics/history.hpp"
#include "solver/gear/gear_rating.hpp"
#include "solver/gear/mesh_dynamics_iso.hpp"
#include "solver/gear/mesh_dynamics_sdof.hpp"
#include "solver/scene/rack_pinion_roots.hpp"

namespace gearsph {
struct Simulation;
struct Scene;
}  // namespace gearsph

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
  double contact_modulus = 0.0;     // E* of pinion and rack [Pa]
  double iso_mesh_stiffness = 0.0;  // c' [N/m per m of face width], ISO 6336-1
  // The largest contact force an elastic mesh can see from the start: the
  // load plus the impact of the initial mismatch of pitch-line speeds on the
  // mesh spring, dv sqrt(k m_rack) (per gear) [N].
  double impact_force_bound_N = 0.0;
  bool quasi_static = false;
  // The masses the lumped mesh model takes (gear/mesh_dynamics_sdof.hpp),
  // per gear: the modelled rack segment's and what the job attaches to it
  // [kg], the whole pinion's polar inertia and what turns with it [kg m^2],
  // and the play between the flanks along the pitch line [m].
  double rack_mass_kg = 0.0, rack_attached_mass_kg = 0.0;
  double pinion_inertia_kg_m2 = 0.0, pinion_attached_inertia_kg_m2 = 0.0;
  double play_m = 0.0;
  // ISO 6336-1 method B at the run's speed and load (loaded runs only).
  std::optional<gear::dynamics::IsoDynamics> iso_dynamics;
  std::string iso_dynamics_note;  // why there is none (outside ISO 6336-1 method B)
  // Static checks: where tooth 0 is loaded ("pitch", "hpstc", "lpstc",
  // "tip" or "radius") and the radius on the pinion [m].
  std::string contact_point;
  double load_radius = 0.0;
  // A resolved static contact (scene.resolve_contact): the point where tooth
  // 0 meets the rack, the flank's tangent there, the particles' spacing
  // over the contact, and the Hertz half-width they resolve, estimated from
  // the load [m]; spacing 0: not resolved.
  struct ResolvedContact {
    double x = 0.0, y = 0.0, tx = 0.0, ty = 0.0, spacing = 0.0, half_width = 0.0;
  } resolved;
  // Particles: body-fitted (graded from fine_spacing at the fillets and
  // active flanks to pinion_spacing in the pinion, spacing in the rack) or
  // a lattice of spacing.
  bool fitted = false;
  double spacing = 0.0, fine_spacing = 0.0;
  double pinion_spacing = 0.0;  // the pinion's bulk (body-fitted: finer than the rack's)
  // The fillets and critical section of every modelled tooth, with the
  // stress recovered on them (rack_pinion_roots.hpp).
  std::shared_ptr<const RootMonitor> roots;
  std::vector<std::size_t> tooth0_particles;
  std::vector<gear::IsoToothForm> iso_by_radius;  // form radius to tip, ascending
  std::string selection;                          // how the modelled teeth were chosen, in words
  // The ISO 6336 rating document of a loaded pair whose materials carry
  // strength (gear/iso6336_simulated.hpp); null: no analysis.rating.
  nlohmann::json rating_document;
  // Why a job that asked for no rating is not rated (its pair is outside
  // what ISO 6336 method B rates): {pointer, message}, or null.
  nlohmann::json rating_refusal;
  // A root crack's way (rack_pinion_crack.hpp): lines where the pinion's
  // body-fitted particles take the fillets' spacing.
  std::vector<std::vector<geometry::Point>> crack_refine;
  double crack_spacing = 0.0;
};

// Particles of no modelled tooth (hub ring, rack) are marked with a number
// no tooth has (teeth are numbered -z..z around the mesh).
inline constexpr int kNoTooth = std::numeric_limits<int>::min();

// Particles whose velocities the history follows: the tooth in mesh at its
// pitch circle on the driving flank, the rack tooth it drives, and the
// middle of the rack's back.
struct GearProbes {
  std::size_t pinion_tooth = 0, rack_tooth = 0, rack_back = 0;
};

// History columns (rack_pinion_histories.cpp): the rack's motion and
// transmission error, the hub's rate and torque, the contact force, per
// modelled tooth its root stress (fillets and critical section) and
// contact force, and the probes' velocities. tooth_of: each particle's
// modelled tooth, or kNoTooth.
void add_gear_histories(Scene& scene, const GearLayout& L, const std::vector<int>& tooth_of,
                        const GearProbes& probes);

// Velocity-stability time (docs/gears.md): the earliest t* after which v(t)
// stays within +/- tolerance of its mean over [t*, end]. -1 if never (the
// signal is still varying at the end); 0 if always.
double velocity_stability_time(const std::vector<double>& t, const std::vector<double>& v,
                               double tolerance);

// The deformable rim below the pinion's root circle [m] (scene.pinion):
// rim_depth_mm, or one module. A fixed depth would hold a module-5 pinion's
// sector closer to its teeth than a module-3 one's, and its mesh stiffness
// with it (+34 % and -9 % against ISO where module 4 read +11 %).
// With backup_ratio (the rim's thickness below the root circle over the
// whole tooth depth, Lewicki & Ballarini's m_B): that ratio times
// `tooth_depth_m` (tip radius less root radius).
double pinion_rim_depth_m(const nlohmann::json& pinion, double tooth_depth_m);

// The pinion teeth of a count ("all" or a number n: n teeth from the one in
// mesh, extended toward where teeth come from, i.e. +k for a clockwise
// pinion, omega <= 0), numbered from the one in mesh, ascending.
std::vector<int> counted_pinion_teeth(const nlohmann::json& choice, int teeth, double omega);

// The pinion teeth a static check (quasi_static) models, ascending: tooth
// 0, which carries the load, with at least its two neighbours, the rim
// beside its fillets, and whatever more the job's modelled_teeth asks for.
// The FE check models the same (fe/gear_fe_job.cpp). `pinion`: scene.pinion
// with its defaults.
std::vector<int> static_check_pinion_teeth(const nlohmann::json& pinion);
// Why, in words, for the summary.
std::string static_check_teeth_reason(const nlohmann::json& pinion);

// analysis.dynamics of a loaded dynamic run (rack_pinion_dynamics.cpp): the
// steady mesh after the start transient, the ringing's damping, and the
// lumped model of the same pair at the run's speed beside ISO 6336-1.
nlohmann::json analyse_mesh_dynamics(const GearLayout& layout, const History& h);

// Scene::ends_early of a loaded dynamic run that asks for `periods` mesh
// periods of steady mesh: it reads the mesh as analyse_mesh_dynamics does,
// once a mesh period, and ends the run once the steady window holds them
// beside the detector's reference periods.
std::function<std::string(const History&)> end_on_steady_mesh(const GearLayout& layout,
                                                              int periods);

// The lumped model of the pair as the scene models it (masses with what is
// attached, a held pinion as infinitely heavy, the play along the line of
// action, the load along it), with a single-pair stiffness k_single [N/m
// per gear] and the double-pair one kIsoDoubleOverSinglePair times it, and
// a damping ratio.
gear::dynamics::SdofModel lumped_mesh_model(const GearLayout& layout, double k_single_N_m,
                                            double damping_ratio);
// Whether the pair has one: a contact ratio between 1 and 2 (two levels).
bool has_lumped_mesh_model(const GearLayout& layout);
// The model's blocks of the scene's description (model.lumped_model): its
// inputs and natural frequency, ISO 6336-1's resonance beside them.
nlohmann::json describe_lumped_model(const GearLayout& layout);
// ISO's c' / C_M per gear [N/m]: the ideal elastic pair's single stiffness.
double ideal_single_pair_stiffness_N_m(const GearLayout& layout);

nlohmann::json analyse_rack_pinion(const GearLayout& layout, const History& h,
                                   const Simulation& final_state);

}  // namespace gearsph::scenes
