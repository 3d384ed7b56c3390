#pragma once
// The lumped cross-check of gear dynamics (docs/dynamics.md): one degree of
// freedom along the line of action,
//
//   m_e x'' + c x' + k(t) g(x - e(t)) = F,
//
// x the dynamic transmission error (relative displacement of the flanks
// along the line of action, positive closing the driving flanks), k(t) the
// mesh stiffness over one mesh cycle (single- and double-pair contact), g
// the backlash dead zone, e(t) the static transmission error excitation and
// F the load along the line of action (Kahraman & Singh, J. Sound Vib. 142
// (1990) 49-75, eq. 1 in the mesh coordinate; Ozguven & Houser, J. Sound
// Vib. 125 (1988)). SI units throughout.
#include <vector>

namespace gearsph::gear::dynamics {

// A periodic function over one mesh cycle, tabulated at positions s in
// [0, 1) (fractions of a mesh cycle, ascending), linear between samples and
// across the period's end.
struct MeshCycleTable {
  std::vector<double> position;
  std::vector<double> value;
  double at(double s) const;  // s any real number: taken modulo 1
  double mean() const;        // exact mean of the piecewise-linear function
  double max() const;
  double min() const;
};

// The mesh stiffness of a spur pair over one mesh cycle from its single-pair
// stiffness and contact ratio eps (1 < eps < 2): two pairs in contact over
// the first eps - 1 of the cycle, one over the rest. `edge` is the fraction of
// a cycle over which each step is ramped linearly (0: a square wave).
MeshCycleTable two_level_stiffness(double k_single_N_m, double k_double_N_m, double contact_ratio,
                                   double edge = 0.0);

// ISO 6336-1:2006, 9.3: the mean mesh stiffness c_gamma_alpha = c' (0.75
// eps_alpha + 0.25) of a spur pair whose single-pair stiffness is c'. For a
// two-level cycle with 1 < eps < 2 its mean is k_s (2 - eps) + k_d (eps - 1);
// equal to c' (0.75 eps + 0.25) for every eps in that range when the
// double-pair stiffness is 1.75 c'. ISO's stiffness over the cycle, read as
// two levels.
inline constexpr double kIsoDoubleOverSinglePair = 1.75;

// k0 (1 + amplitude cos(2 pi s)) sampled at n points: the textbook
// parametric excitation (Mathieu's equation).
MeshCycleTable harmonic_table(double mean, double amplitude, int samples);

// The masses along the line of action.
//
// A pinion of polar inertia J turning theta moves its flank along the line
// of action by r_b theta: kinetic energy J theta'^2 / 2 = (J / r_b^2) x'^2 /
// 2, so its mass on the line is J / r_b^2 (Ozguven & Houser 1988).
double pinion_mass_on_line_of_action(double inertia_kg_m2, double base_radius_m);
// A rack translating u along its pitch line (x) meets a line of action at
// the pressure angle alpha to that line: its flank's displacement along the
// line is u cos(alpha), so its kinetic energy m u'^2 / 2 = (m / cos^2 alpha)
// x'^2 / 2 and its mass on the line is m / cos^2(alpha). (Equivalently in x:
// the mesh spring k_n along the line acts on u as k_n cos^2 alpha, and the
// rack's mode is sqrt(k_n cos^2 alpha / m), the same frequency.)
double rack_mass_on_line_of_action(double mass_kg, double pressure_angle_rad);
// Two masses on either side of the mesh spring: m1 m2 / (m1 + m2); an
// infinite one (a pinion held at speed) leaves the other.
double effective_mesh_mass(double m1_kg, double m2_kg);

// sqrt(k / m) / (2 pi) [Hz].
double natural_frequency_Hz(double stiffness_N_m, double mass_kg);
// c = 2 zeta sqrt(k m): viscous mesh damping of a damping ratio on the
// mean stiffness.
double damping_coefficient(double damping_ratio, double stiffness_N_m, double mass_kg);

// The backlash dead zone (Kahraman & Singh 1990, eq. 2, shifted so that the
// driving flanks touch at 0): u on the driving flank (u > 0), nothing
// through the play (-backlash <= u <= 0), u + backlash on the reverse flank.
double backlash_deflection(double u_m, double backlash_m);

struct SdofModel {
  double mass_kg = 0.0;        // m_e along the line of action
  MeshCycleTable stiffness;    // k over one mesh cycle [N/m]
  MeshCycleTable error;        // e over one mesh cycle [m]; empty: none
  double damping_ratio = 0.0;  // on the mean stiffness; acts through the mesh, in contact only
  double backlash_m = 0.0;     // total play between the flanks along the line of action
  double load_N = 0.0;         // F along the line of action
};

// The mesh force k(t) g(x - e) + c x' while the flanks touch (0 through the
// play): what the teeth carry. Damping acts through the contact only, so a
// rack flying through the play feels no force.
double mesh_force(const SdofModel& m, double s, double x, double v);

struct SdofState {
  double x = 0.0, v = 0.0;
};

struct SdofOptions {
  int steps_per_mesh_period_min = 64;
  // The step also resolves the stiffest mode: at least this many steps per
  // period of sqrt(k_max / m_e).
  int steps_per_natural_period = 80;
  int measured_periods = 20;
  // Steady: the extremes of force and x over a window of `window` mesh
  // periods differ from the previous window's by less than `tolerance` of
  // their swing over the window (at least 1e-3 of the load F and of the
  // static deflection F / k_mean).
  int window_periods = 4;
  double tolerance = 1e-3;
  int max_transient_periods = 4000;
};

// One speed's steady response, measured over SdofOptions::measured_periods
// after the transient.
struct SdofResponse {
  double mesh_frequency_Hz = 0.0;
  bool steady = false;
  int transient_periods = 0;  // mesh periods before the measurement
  double mean_force_N = 0.0, peak_force_N = 0.0, min_force_N = 0.0;
  double K_v = 0.0;                                          // peak over mean mesh force
  double dte_mean_m = 0.0, dte_pp_m = 0.0, dte_rms_m = 0.0;  // rms about the mean
  double contact_loss_fraction = 0.0;                        // of time with the flanks apart
  double reverse_contact_fraction = 0.0;
};

// Runs the model at one mesh frequency from `state` (left at the end of
// the measurement, so that a sweep continues from it).
SdofResponse respond_at(const SdofModel& model, double mesh_frequency_Hz, SdofState& state,
                        const SdofOptions& opt = {});

// x after each of `steps` steps of dt from `state`, the mesh held at phase
// s = 0 (no excitation): the pair's free ringing.
std::vector<double> free_response(const SdofModel& model, SdofState state, double dt, int steps);

// Half the peak-to-peak x of each of `periods` mesh periods from `state`:
// how an unsteady response grows or decays (a parametric instability).
std::vector<double> period_amplitudes(const SdofModel& model, double mesh_frequency_Hz,
                                      SdofState& state, int periods, const SdofOptions& opt = {});

// The static state under the load (x = e + F / k at s = 0, at rest): where a
// sweep starts.
SdofState static_state(const SdofModel& model);

// A sweep through mesh frequencies in the given order, each speed starting
// from the state the previous one left (a slow sweep's continuation: up and
// down sweeps differ where the response has two branches).
std::vector<SdofResponse> sweep(const SdofModel& model, const std::vector<double>& frequencies_Hz,
                                const SdofOptions& opt = {});

// The abscissa of the largest value, refined by the parabola through it and
// its two neighbours (the end point itself at an end).
double peak_abscissa(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace gearsph::gear::dynamics
