// What a gear engineer reads off a rack-and-pinion run (docs/gears.md):
// peak stresses, the velocity-stability time, contact forces, root stress
// per tooth against Lewis and ISO 6336-3, transmission error, the mesh
// stiffness it implies under load, load sharing and the measured contact
// ratio.
#include <algorithm>
#include <cmath>

#include "solver/scene/rack_pinion.hpp"

namespace gearsph::scenes {

double velocity_stability_time(const std::vector<double>& t, const std::vector<double>& v,
                               double tolerance) {
  const std::size_t n = std::min(t.size(), v.size());
  if (n < 2) return -1.0;
  // Scan backwards keeping the running mean, min and max of v over [k, end].
  double sum = 0.0, lo = 1e300, hi = -1e300;
  std::size_t first_ok = n;
  for (std::size_t k = n; k-- > 0;) {
    sum += v[k];
    lo = std::min(lo, v[k]);
    hi = std::max(hi, v[k]);
    const double mean = sum / static_cast<double>(n - k);
    const double band = tolerance * std::abs(mean);
    if (hi - mean <= band && mean - lo <= band) {
      first_ok = k;
    } else if (first_ok != n) {
      break;  // once the band is violated further back, later starts stay the answer
    }
  }
  if (first_ok >= n - 1) return -1.0;  // only the last sample: never settled
  return t[first_ok] - t.front();
}

namespace {

double max_of(const std::vector<double>& v) {
  double m = -1e300;
  for (double x : v) m = std::max(m, x);
  return m;
}

}  // namespace

nlohmann::json analyse_rack_pinion(const GearLayout& L, const History& h) {
  nlohmann::json a;
  const std::vector<double> t = h.column("time_s");
  const double b = L.face_width_m, m = L.module_m;

  // Velocity stability of the transmitted motion (the rack) and of each probe.
  const std::vector<double> vr = h.column("rack_vx_m_s");
  const double t_stable = velocity_stability_time(t, vr, 0.05);
  a["velocity_stability"] = {
      {"definition",
       "earliest time after which the rack's mean x velocity stays within +/-5 % of its mean "
       "over the rest of the run; -1 if it never settles"},
      {"rack_s", t_stable}};
  for (const char* probe : {"pinion_tooth", "rack_tooth", "rack_back"}) {
    const std::string col = std::string("probe_") + probe + "_vx_m_s";
    a["velocity_stability"][std::string(probe) + "_s"] =
        velocity_stability_time(t, h.column(col), 0.05);
  }
  const std::vector<double> fc = h.column("contact_force_N");
  const double f_max = max_of(fc);
  std::size_t k_max = 0;
  for (std::size_t k = 0; k < fc.size(); ++k) {
    if (fc[k] == f_max) k_max = k;
  }

  // Root stress per modelled tooth, and the references. Ft for the formulas:
  // the resisting load when one is applied, else the peak contact force's
  // tangential part (contact force along the line of action: Ft = F cos alpha).
  const double ft = L.load_N > 0 ? L.load_N : f_max * std::cos(L.pressure_angle);
  nlohmann::json teeth = nlohmann::json::array();
  double root_max = 0.0;
  for (int k : L.pinion_teeth) {
    const std::string sk = std::to_string(k);
    const std::vector<double> rs = h.column("root_stress_t" + sk + "_Pa");
    const std::vector<double> tf = h.column("tooth_force_t" + sk + "_N");
    const double peak = max_of(rs);
    root_max = std::max(root_max, peak);
    teeth.push_back(
        {{"tooth", k}, {"max_root_stress_Pa", peak}, {"max_tooth_force_N", max_of(tf)}});
  }
  a["pinion_teeth"] = teeth;
  a["max_root_stress_Pa"] = root_max;
  a["root_stress_references"] = {
      {"tangential_force_N", ft},
      {"lewis_Y", L.lewis_Y},
      {"lewis_Pa", L.lewis_Y > 0 ? ft / (b * m * L.lewis_Y) : 0.0},
      {"iso_tip",
       {{"Y_F", L.iso_tip.Y_F},
        {"Y_S", L.iso_tip.Y_S},
        {"sigma_F0_Pa", ft / (b * m) * L.iso_tip.Y_F * L.iso_tip.Y_S}}},
      {"iso_hpstc",
       {{"Y_F", L.iso_hpstc.Y_F},
        {"Y_S", L.iso_hpstc.Y_S},
        {"load_radius_m", L.iso_hpstc.load_radius},
        {"sigma_F0_Pa", ft / (b * m) * L.iso_hpstc.Y_F * L.iso_hpstc.Y_S}}},
      {"s_Fn_m", L.iso_tip.s_Fn},
      {"rho_F_m", L.iso_tip.rho_F}};

  // Load sharing and the contact ratio actually seen: a tooth carries load
  // when its contact force exceeds 5 % of the total at that instant.
  double pairs_sum = 0.0;
  std::size_t pairs_n = 0;
  for (std::size_t row = 0; row < h.rows(); ++row) {
    const double total = fc[row];
    if (total <= 1e-3 * f_max || f_max <= 0) continue;
    int carrying = 0;
    for (int k : L.pinion_teeth) {
      const double f =
          h.at(row, static_cast<std::size_t>(h.index("tooth_force_t" + std::to_string(k) + "_N")));
      carrying += f > 0.05 * total ? 1 : 0;
    }
    pairs_sum += carrying;
    ++pairs_n;
  }
  a["contact_ratio"] = {
      {"theory", L.path.contact_ratio},
      {"measured_mean_teeth_in_contact", pairs_n ? pairs_sum / static_cast<double>(pairs_n) : 0.0}};

  // Transmission error and, under a steady load, the mesh stiffness it implies:
  // c' = F_bt / (b * delta_n) with delta the mean lag of the rack over the second
  // half of the run (N/(mm um), ISO 6336-1's unit).
  const std::vector<double> te = h.column("transmission_error_m");
  double te_mean = 0.0, te_lo = 1e300, te_hi = -1e300;
  std::size_t count = 0;
  for (std::size_t k = 0; k < te.size(); ++k) {
    if (t[k] < 0.5 * t.back()) continue;
    te_mean += te[k];
    te_lo = std::min(te_lo, te[k]);
    te_hi = std::max(te_hi, te[k]);
    ++count;
  }
  te_mean = count ? te_mean / static_cast<double>(count) : 0.0;
  a["transmission_error"] = {{"mean_second_half_m", te_mean},
                             {"peak_to_peak_second_half_m", count ? te_hi - te_lo : 0.0}};
  if (L.load_N > 0 && std::abs(te_mean) > 0) {
    // Along the line of action: F_bt = F_t / cos(alpha), delta_n = delta_x cos(alpha).
    const double c = std::cos(L.pressure_angle);
    a["mesh_stiffness_N_per_mm_um"] = L.load_N / (c * c) / (1e3 * b) / (1e6 * std::abs(te_mean));
  }

  a["summary_fields"] = {
      {"velocity_stability_time_s", t_stable},
      {"max_contact_force_N", f_max},
      {"max_contact_force_time_s", t.empty() ? 0.0 : t[k_max]},
      {"max_root_stress_Pa", root_max},
      {"modelled_teeth",
       {{"pinion", L.pinion_teeth}, {"rack", L.rack_teeth.size()}, {"reason", L.selection}}}};
  return a;
}

}  // namespace gearsph::scenes
