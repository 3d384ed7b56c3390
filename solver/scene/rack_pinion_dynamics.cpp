// The dynamics of a loaded rack-and-pinion run (docs/dynamics.md): the
// steady mesh after the start transient (diagnostics/steady_mesh.hpp), the
// damping of the start's free ringing, and the lumped model of the same
// pair (gear/mesh_dynamics_sdof.hpp) at the run's speed, with ISO 6336-1's
// resonance beside it.
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "solver/diagnostics/steady_mesh.hpp"
#include "solver/scene/rack_pinion.hpp"

namespace gearsph::scenes {

namespace {

constexpr double kPi = std::numbers::pi;

double mean_over_second_half(const std::vector<double>& t, const std::vector<double>& v) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < t.size() && k < v.size(); ++k) {
    if (t[k] < 0.5 * (t.front() + t.back())) continue;
    sum += v[k];
    ++n;
  }
  return n ? sum / static_cast<double>(n) : 0.0;
}

nlohmann::json sdof_json(const gear::dynamics::SdofResponse& r) {
  return {{"mesh_frequency_Hz", r.mesh_frequency_Hz},
          {"steady", r.steady},
          {"mean_force_N", r.mean_force_N},
          {"peak_force_N", r.peak_force_N},
          {"K_v", r.K_v},
          {"dte_pp_m", r.dte_pp_m},
          {"dte_rms_m", r.dte_rms_m},
          {"contact_loss_fraction", r.contact_loss_fraction}};
}

}  // namespace

double ideal_single_pair_stiffness_N_m(const GearLayout& L) {
  return L.iso_mesh_stiffness / gear::kIsoMeasuredOverTheoretical * L.face_width_m;
}

gear::dynamics::SdofModel lumped_mesh_model(const GearLayout& L, double k_single,
                                            double damping_ratio) {
  namespace dyn = gear::dynamics;
  dyn::SdofModel m;
  // A pinion held at its speed is infinitely heavy on the line of action;
  // a torque-driven one carries its whole inertia and what turns with it.
  const double pinion =
      L.torque_Nm ? dyn::pinion_mass_on_line_of_action(
                        L.pinion_inertia_kg_m2 + L.pinion_attached_inertia_kg_m2, L.base_radius)
                  : std::numeric_limits<double>::infinity();
  const double rack =
      dyn::rack_mass_on_line_of_action(L.rack_mass_kg + L.rack_attached_mass_kg, L.pressure_angle);
  m.mass_kg = dyn::effective_mesh_mass(pinion, rack);
  m.stiffness = dyn::two_level_stiffness(k_single, dyn::kIsoDoubleOverSinglePair * k_single,
                                         L.path.contact_ratio);
  m.damping_ratio = damping_ratio;
  // The play and the load along the line of action: a pitch-line length
  // times cos(alpha), a tangential force over it.
  m.backlash_m = L.play_m * std::cos(L.pressure_angle);
  m.load_N = L.load_N / std::cos(L.pressure_angle);
  return m;
}

bool has_lumped_mesh_model(const GearLayout& L) {
  return L.path.contact_ratio > 1.0 && L.path.contact_ratio < 2.0;
}

nlohmann::json describe_lumped_model(const GearLayout& L) {
  namespace dyn = gear::dynamics;
  if (!has_lumped_mesh_model(L)) {
    return {{"note",
             "no lumped model: its two-level stiffness needs a contact ratio between 1 "
             "and 2, this pair's is " +
                 std::to_string(L.path.contact_ratio)}};
  }
  const double k_s = ideal_single_pair_stiffness_N_m(L);
  const dyn::SdofModel m = lumped_mesh_model(L, k_s, 0.0);
  nlohmann::json out = {
      {"equation",
       "m_e x'' + c x' + k(t) g(x) = F along the line of action (Kahraman & Singh 1990)"},
      {"mass_on_line_of_action_kg", m.mass_kg},
      {"rack_mass_kg", L.rack_mass_kg},
      {"rack_attached_mass_kg", L.rack_attached_mass_kg},
      {"pinion", L.torque_Nm ? "torque-driven: J / r_b^2" : "held at speed: infinitely heavy"},
      {"single_pair_stiffness_N_m", k_s},
      {"double_pair_stiffness_N_m", dyn::kIsoDoubleOverSinglePair * k_s},
      {"stiffness_from",
       "ISO 6336-1 c' / C_M (the ideal elastic pair) per face width; two levels over the mesh "
       "cycle from the contact ratio, the double-pair level 1.75 c' (ISO's c_gamma_alpha)"},
      {"mean_stiffness_N_m", m.stiffness.mean()},
      {"contact_ratio", L.path.contact_ratio},
      {"backlash_along_line_of_action_m", m.backlash_m},
      {"load_along_line_of_action_N", m.load_N},
      {"natural_frequency_Hz", dyn::natural_frequency_Hz(m.stiffness.mean(), m.mass_kg)}};
  if (L.iso_dynamics) {
    const dyn::IsoDynamics& iso = *L.iso_dynamics;
    out["iso6336_1_method_b"] = {{"c_prime_N_mm_um", iso.c_prime_N_mm_um},
                                 {"c_gamma_alpha_N_mm_um", iso.c_gamma_alpha_N_mm_um},
                                 {"m_red_kg_per_mm", iso.m_red_kg_mm},
                                 {"n_E1_rpm", iso.n_E1_rpm},
                                 {"resonance_mesh_Hz", iso.resonance_mesh_Hz},
                                 {"N", iso.N},
                                 {"K_v", iso.K_v},
                                 {"range", iso.range},
                                 {"note",
                                  "for a rack ISO takes the pinion's mass alone (the rack as "
                                  "infinitely heavy), the opposite of a pinion held at speed "
                                  "driving a free rack"}};
  } else if (!L.iso_dynamics_note.empty()) {
    out["iso6336_1_method_b"] = {{"status", "not_applicable"}, {"reason", L.iso_dynamics_note}};
  }
  return out;
}

std::function<std::string(const History&)> end_on_steady_mesh(const GearLayout& L, int periods) {
  // The detector compares each period with the last three: those are no
  // part of the window a user asked for.
  constexpr int kReferencePeriods = 3;
  const double f_mesh = std::abs(L.omega) * L.teeth / (2.0 * kPi);
  double next_check_s = 0.0;
  return [f_mesh, periods, next_check_s](const History& h) mutable -> std::string {
    if (!(f_mesh > 0.0) || h.rows() < 2) return {};
    const double t = h.at(h.rows() - 1, static_cast<std::size_t>(h.index("time_s")));
    if (t < next_check_s) return {};
    next_check_s = t + 1.0 / f_mesh;
    diagnostics::MeshHistories mh;
    mh.t = h.column("time_s");
    mh.total_force_N = h.column("contact_force_N");
    mh.mesh_frequency_Hz = f_mesh;
    const diagnostics::SteadyMesh s = diagnostics::steady_mesh(mh);
    if (!s.steady || s.steady_periods < periods + kReferencePeriods) return {};
    char text[160];
    std::snprintf(text, sizeof text,
                  "the mesh was steady from %.6g s for %d mesh periods (%d asked for, "
                  "/scene/steady_mesh_periods)",
                  s.steady_from_s, s.steady_periods, periods);
    return text;
  };
}

nlohmann::json analyse_mesh_dynamics(const GearLayout& L, const History& h) {
  namespace dyn = gear::dynamics;
  diagnostics::MeshHistories mh;
  mh.t = h.column("time_s");
  mh.total_force_N = h.column("contact_force_N");
  // Along the line of action: the rack's lag along x times cos(alpha).
  for (double te : h.column("transmission_error_m")) {
    mh.dte_m.push_back(te * std::cos(L.pressure_angle));
  }
  for (int k : L.pinion_teeth) {
    mh.tooth_force_N.push_back({k, h.column("tooth_force_t" + std::to_string(k) + "_N")});
  }
  const double omega = std::abs(mean_over_second_half(mh.t, h.column("pinion_omega_rad_s")));
  mh.mesh_frequency_Hz = omega * L.teeth / (2.0 * kPi);
  const diagnostics::SteadyMesh s = diagnostics::steady_mesh(mh);

  nlohmann::json teeth = nlohmann::json::array();
  for (const diagnostics::ToothLoad& t : s.teeth) {
    teeth.push_back({{"tooth", t.tooth},
                     {"mean_force_N", t.mean_N},
                     {"peak_force_N", t.peak_N},
                     {"loaded_fraction", t.loaded_fraction}});
  }
  nlohmann::json out = {
      {"mesh_frequency_Hz", s.mesh_frequency_Hz},
      {"steady", s.steady},
      {"steady_from_s", s.steady_from_s},
      {"steady_periods", s.steady_periods},
      {"mesh_periods_in_run", s.periods_in_run},
      {"transient_detection",
       "steady from the first whole mesh period after which every period's mean and peak mesh "
       "force stay within 5 % of the last three periods' mean"},
      {"mean_force_N", s.mean_force_N},
      {"peak_force_N", s.peak_force_N},
      {"K_v", s.K_v},
      {"load_along_line_of_action_N", L.load_N / std::cos(L.pressure_angle)},
      {"dte_mean_m", s.dte_mean_m},
      {"dte_pp_m", s.dte_pp_m},
      {"dte_rms_m", s.dte_rms_m},
      {"dte_definition",
       "the rack's lag behind ideal rolling along the line of action; rms "
       "about its mean over the window"},
      {"contact_loss_fraction", s.contact_loss_fraction},
      {"teeth", teeth}};
  if (!s.note.empty()) out["note"] = s.note;

  // The start's free ringing (up to the steady mesh, or over the run's
  // first half) gives the pair's damping and its ringing frequency.
  const double t_end = s.steady ? s.steady_from_s : 0.5 * (mh.t.front() + mh.t.back());
  const diagnostics::RingDown ring = diagnostics::ring_down(mh.t, mh.dte_m, mh.t.front(), t_end);
  const nlohmann::json lumped = describe_lumped_model(L);
  out["ringing"] = {{"damping_ratio", ring.damping_ratio},
                    {"frequency_Hz", ring.frequency_Hz},
                    {"extremes", ring.extremes},
                    {"from",
                     "log decrement of the transmission error's extremes in the start "
                     "transient; -1: fewer than three extremes"}};
  out["lumped_model"] = lumped;
  if (ring.damping_ratio > 0.0 && s.mesh_frequency_Hz > 0.0 && L.load_N > 0.0 &&
      has_lumped_mesh_model(L)) {
    const dyn::SdofModel m =
        lumped_mesh_model(L, ideal_single_pair_stiffness_N_m(L), ring.damping_ratio);
    dyn::SdofState y = dyn::static_state(m);
    out["lumped_model"]["at_run_speed"] = sdof_json(dyn::respond_at(m, s.mesh_frequency_Hz, y));
  }
  return out;
}

}  // namespace gearsph::scenes
