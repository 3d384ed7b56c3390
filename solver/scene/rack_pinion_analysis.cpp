// What a gear engineer reads off a rack-and-pinion run (docs/gears.md):
// peak stresses, the velocity-stability time, contact forces, root stress
// per tooth against Lewis and ISO 6336-3, transmission error, the mesh
// stiffness it implies under load, load sharing and the measured contact
// ratio.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "solver/diagnostics/hertz_fit.hpp"
#include "solver/gear/iso6336_simulated.hpp"
#include "solver/physics/simulation.hpp"
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

// The fillet curves of one tooth as a gear engineer plots them: stress
// against arc length from the middle of the tooth space (compression
// fillet: sigma_3, tension fillet: sigma_1).
nlohmann::json fillet_curves(const gear::ToothFillets& f, const ToothRootState& r) {
  return {{"tension",
           {{"arc_m", f.tension.arc},
            {"radius_m", f.tension.radius},
            {"sigma1_Pa", r.fillet.tension_curve}}},
          {"compression",
           {{"arc_m", f.compression.arc},
            {"radius_m", f.compression.radius},
            {"sigma3_Pa", r.fillet.compression_curve}}}};
}

// Where the contact load on tooth 0 acts: the contact-force-weighted mean
// radius of its particles in the final state.
double tooth0_load_radius(const GearLayout& L, const Simulation& sim) {
  const Particles& p = sim.particles;
  double wsum = 0.0, rsum = 0.0;
  for (std::size_t i : L.tooth0_particles) {
    const double w = p.mass[i] * std::hypot(p.contact_ax[i], p.contact_ay[i]);
    wsum += w;
    rsum += w * std::hypot(p.x[i] - L.cx, p.y[i] - L.cy);
  }
  return wsum > 0.0 ? rsum / wsum : 0.0;
}

// Where the mesh's compliance sits in a static check, each part's
// deflection along the contact normal per unit line load [um mm / N]:
// the pinion (tooth and body to the held hub) at its contact point, the
// contact (the pair law's overlap: near field within its stiffness bound), and the
// rack (tooth and body) from its contact point to its mean displacement,
// whose sum is the transmission error's 1/c'. Contact points are the
// contact-force-weighted smoothed points of each body's loaded particles
// (physics/contact_smoothing.hpp), their displacements from the reference.
nlohmann::json compliance_split(const Simulation& sim, double delta_total_m, double load_N_per_mm) {
  const Particles& p = sim.particles;
  const ContactState& st = sim.contact_state;
  const bool smooth = st.smoothing_built;
  // The normal: the direction of the contact force on the pinion (body 0).
  double fx = 0.0, fy = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.body[i] != 0) continue;
    fx += p.mass[i] * p.contact_ax[i];
    fy += p.mass[i] * p.contact_ay[i];
  }
  const double fn = std::hypot(fx, fy);
  if (fn <= 0.0 || load_N_per_mm <= 0.0) return nullptr;
  const double nx = fx / fn, ny = fy / fn;
  auto contact_point_displacement = [&](int body) {
    double wsum = 0.0, usum = 0.0;
    for (std::size_t i = 0; i < p.n; ++i) {
      if (p.body[i] != body) continue;
      const double w = p.mass[i] * std::hypot(p.contact_ax[i], p.contact_ay[i]);
      if (w <= 0.0) continue;
      double ux = p.x[i] - p.x0[i], uy = p.y[i] - p.y0[i];
      if (smooth && st.smooth_rows[i] != st.smooth_rows[i + 1]) {
        ux = uy = 0.0;
        for (std::uint32_t e = st.smooth_rows[i]; e < st.smooth_rows[i + 1]; ++e) {
          const std::uint32_t k = st.smooth_k[e];
          ux += st.smooth_w[e] * (p.x[k] - p.x0[k]);
          uy += st.smooth_w[e] * (p.y[k] - p.y0[k]);
        }
      }
      wsum += w;
      usum += w * (ux * nx + uy * ny);
    }
    return wsum > 0.0 ? usum / wsum : 0.0;
  };
  const double pinion = contact_point_displacement(0);
  const double rack = contact_point_displacement(1);
  const double to_um = 1e6 / load_N_per_mm;
  return {{"pinion_um_mm_per_N", pinion * to_um},
          {"contact_um_mm_per_N", (rack - pinion) * to_um},
          {"rack_um_mm_per_N", (delta_total_m - rack) * to_um},
          {"total_um_mm_per_N", delta_total_m * to_um}};
}

// ISO 6336-3 form factors at a load radius, interpolated in the table.
gear::IsoToothForm iso_at(const GearLayout& L, double radius) {
  const std::vector<gear::IsoToothForm>& t = L.iso_by_radius;
  if (radius <= t.front().load_radius) return t.front();
  for (std::size_t k = 1; k < t.size(); ++k) {
    if (radius <= t[k].load_radius) {
      const double w = (radius - t[k - 1].load_radius) / (t[k].load_radius - t[k - 1].load_radius);
      gear::IsoToothForm f = t[k - 1];
      f.Y_F += w * (t[k].Y_F - f.Y_F);
      f.Y_S += w * (t[k].Y_S - f.Y_S);
      f.load_radius = radius;
      return f;
    }
  }
  return t.back();
}

// The last sample at which a series takes the value `v` (0 if none).
std::size_t last_index_of(const std::vector<double>& series, double v) {
  std::size_t k_at = 0;
  for (std::size_t k = 0; k < series.size(); ++k) {
    if (series[k] == v) k_at = k;
  }
  return k_at;
}

// Velocity stability of the transmitted motion (the rack, t_rack) and of
// each probe.
nlohmann::json velocity_stability(const History& h, const std::vector<double>& t, double t_rack) {
  nlohmann::json out = {
      {"definition",
       "earliest time after which the rack's mean x velocity stays within +/-5 % of its mean "
       "over the rest of the run; -1 if it never settles"},
      {"rack_s", t_rack}};
  for (const char* probe : {"pinion_tooth", "rack_tooth", "rack_back"}) {
    const std::string col = std::string("probe_") + probe + "_vx_m_s";
    out[std::string(probe) + "_s"] = velocity_stability_time(t, h.column(col), 0.05);
  }
  return out;
}

// Root stress per modelled tooth, and the references. Ft for the formulas:
// the resisting load when one is applied, else the peak contact force's
// tangential part (contact force along the line of action: Ft = F cos alpha).
void add_root_stresses(nlohmann::json& a, const GearLayout& L, const History& h, double f_max) {
  const double b = L.face_width_m, m = L.module_m;
  const double ft = L.load_N > 0 ? L.load_N : f_max * std::cos(L.pressure_angle);
  nlohmann::json teeth = nlohmann::json::array();
  double root_max = 0.0, bending_max = 0.0;
  for (int k : L.pinion_teeth) {
    const std::string sk = std::to_string(k);
    const std::vector<double> rs = h.column("root_stress_t" + sk + "_Pa");
    const std::vector<double> tf = h.column("tooth_force_t" + sk + "_N");
    const std::vector<double> rb = h.column("root_bending_t" + sk + "_Pa");
    const double peak = max_of(rs);
    root_max = std::max(root_max, peak);
    bending_max = std::max(bending_max, max_of(rb));
    teeth.push_back({{"tooth", k},
                     {"max_root_stress_Pa", peak},
                     {"max_root_bending_stress_Pa", max_of(rb)},
                     {"max_tooth_force_N", max_of(tf)}});
  }
  a["pinion_teeth"] = teeth;
  a["max_root_stress_Pa"] = root_max;
  a["max_root_bending_stress_Pa"] = bending_max;
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
      {"iso_pitch_point",
       {{"Y_F", L.iso_pitch.Y_F},
        {"Y_S", L.iso_pitch.Y_S},
        {"load_radius_m", L.iso_pitch.load_radius},
        {"sigma_F0_Pa", ft / (b * m) * L.iso_pitch.Y_F * L.iso_pitch.Y_S}}},
      {"s_Fn_m", L.iso_tip.s_Fn},
      {"rho_F_m", L.iso_tip.rho_F}};
}

// Load sharing and the contact ratio actually seen: a tooth carries load
// when its contact force exceeds 5 % of the total at that instant.
nlohmann::json measured_contact_ratio(const GearLayout& L, const History& h,
                                      const std::vector<double>& fc, double f_max) {
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
  return {
      {"theory", L.path.contact_ratio},
      {"measured_mean_teeth_in_contact", pairs_n ? pairs_sum / static_cast<double>(pairs_n) : 0.0}};
}

// Transmission error and, under a steady load, the mesh stiffness it implies:
// c' = F_bt / (b * delta_n) with delta the mean lag of the rack over the second
// half of the run (N/(mm um), ISO 6336-1's unit). Returns that mean lag [m].
double add_transmission_error(nlohmann::json& a, const GearLayout& L, const History& h,
                              const std::vector<double>& t) {
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
    a["mesh_stiffness_N_per_mm_um"] =
        L.load_N / (c * c) / (1e3 * L.face_width_m) / (1e6 * std::abs(te_mean));
  }
  a["iso_mesh_stiffness_N_per_mm_um"] = 1e-9 * L.iso_mesh_stiffness;
  // c'_th, the ideal elastic pair the particles model (docs/gears.md, "Which
  // ISO number to compare with").
  a["iso_theoretical_mesh_stiffness_N_per_mm_um"] =
      1e-9 * L.iso_mesh_stiffness / gear::kIsoMeasuredOverTheoretical;
  return te_mean;
}

// Static check (validation.md 7): tooth 0 (modelled tooth i0) loaded alone
// at its contact point (scene.contact_point), relaxed. The fillet stresses
// recovered on the true outline against ISO 6336-3 with the load where it
// was placed (sigma_F0 = Ft / (b m) Y_F Y_S, Ft tooth 0's share), the
// nominal bending of the critical section against ISO's Y_F alone, and
// Lewis.
nlohmann::json static_root_check(const GearLayout& L, const History& h,
                                 const Simulation& final_state, std::size_t i0) {
  const double b = L.face_width_m, m = L.module_m;
  const ToothRootState& root = L.roots->at(final_state)[i0];
  const std::size_t last = h.rows() - 1;
  const double tooth_force = h.at(last, static_cast<std::size_t>(h.index("tooth_force_t0_N")));
  const double lewis = L.lewis_Y > 0 ? L.load_N / (b * m * L.lewis_Y) : 0.0;
  const gear::IsoToothForm form = iso_at(L, L.load_radius);
  // ISO's Ft is the load on the one tooth: tooth 0's share of the rack
  // force (all of it when it meets the only rack tooth).
  const double ft0 = tooth_force * std::cos(L.pressure_angle);
  const double iso = ft0 / (b * m) * form.Y_F * form.Y_S;
  const double iso_nominal = ft0 / (b * m) * form.Y_F;
  const double bending = root.section_nominal_bending_Pa;
  const double sigma = root.root_stress_Pa;
  constexpr double kDeg = 180.0 / 3.141592653589793;
  const double width = L.roots->section_width(i0);
  return {{"contact_point", L.contact_point},
          {"load_radius_m", L.load_radius},
          {"measured_load_radius_m", tooth0_load_radius(L, final_state)},
          {"tooth0_force_N", tooth_force},
          {"load_carried_by_tooth0", ft0 / L.load_N},
          {"fillet_tension_peak_Pa", root.fillet.tension.stress_Pa},
          {"fillet_tension_peak_radius_m", root.fillet.tension.radius_m},
          {"fillet_tension_peak_angle_deg", kDeg * root.fillet.tension.angle_rad},
          {"fillet_compression_peak_Pa", root.fillet.compression.stress_Pa},
          {"fillet_compression_peak_radius_m", root.fillet.compression.radius_m},
          {"fillet_compression_peak_angle_deg", kDeg * root.fillet.compression.angle_rad},
          {"fillet_stress_at_iso30_Pa", root.fillet.tension.at_iso30_Pa},
          // How the fillet was read: "stretch" on body-fitted particles,
          // "stress_fit" on the lattice (rack_pinion_roots.hpp), and the
          // stress fit's values for contrast.
          {"fillet_reading", L.roots->from_stretch() ? "stretch" : "stress_fit"},
          {"fillet_from_stress_fit",
           {{"tension_peak_Pa", root.fillet_stress_fit.tension.stress_Pa},
            {"compression_peak_Pa", root.fillet_stress_fit.compression.stress_Pa},
            {"at_iso30_Pa", root.fillet_stress_fit.tension.at_iso30_Pa}}},
          {"iso_sigma_F0_Pa", iso},
          {"iso_Y_F_at_load", form.Y_F},
          {"iso_Y_S_at_load", form.Y_S},
          {"fillet_tension_peak_error_vs_iso", (root.fillet.tension.stress_Pa - iso) / iso},
          {"fillet_iso30_error_vs_iso", (root.fillet.tension.at_iso30_Pa - iso) / iso},
          {"root_stress_Pa", sigma},
          {"root_section",
           {{"chord_m", width},
            {"normal_force_N_per_m", root.section_normal_force_N_per_m},
            {"bending_moment_N", root.section_bending_moment_N},
            {"nominal_bending_stress_Pa", bending},
            {"mean_normal_stress_Pa", root.section_normal_force_N_per_m / width}}},
          {"nominal_bending_stress_Pa", bending},
          {"iso_nominal_Pa", iso_nominal},
          {"nominal_error_vs_iso", (bending - iso_nominal) / iso_nominal},
          {"lewis_Pa", lewis},
          {"nominal_error_vs_lewis", lewis > 0 ? (bending - lewis) / lewis : 0.0},
          {"fillet_curves", fillet_curves(L.roots->fillets(i0), root)},
          // Where tooth 0 is (reference frame; a static check's displacements
          // are microns): the window of the FE check's tooth figures, for its
          // field to be drawn beside them.
          {"tooth0_box_m", gear::tooth_window(L.roots->fillets(i0), L.tip_radius)},
          {"particles", L.fitted ? "body_fitted" : "lattice"},
          {"spacing_m", L.spacing},
          {"pinion_spacing_m", L.pinion_spacing},
          {"fine_spacing_m", L.fine_spacing}};
}

// The static check's mesh stiffness against ISO 6336-1 and where the
// compliance sits, from the measured stiffness and transmission error.
void add_static_mesh_stiffness(nlohmann::json& sc, double mesh_stiffness, const GearLayout& L,
                               const Simulation& final_state, double te_mean) {
  sc["mesh_stiffness_N_per_mm_um"] = mesh_stiffness;
  sc["iso_mesh_stiffness_N_per_mm_um"] = 1e-9 * L.iso_mesh_stiffness;
  sc["mesh_stiffness_error_vs_iso"] = mesh_stiffness / (1e-9 * L.iso_mesh_stiffness) - 1.0;
  // The ideal elastic pair's stiffness, c' without ISO's C_M for real gears
  // (docs/gears.md, "Which ISO number to compare with"): the model's truth
  // lies between the two.
  const double theoretical = 1e-9 * L.iso_mesh_stiffness / gear::kIsoMeasuredOverTheoretical;
  sc["iso_theoretical_mesh_stiffness_N_per_mm_um"] = theoretical;
  sc["mesh_stiffness_error_vs_iso_theoretical"] = mesh_stiffness / theoretical - 1.0;
  // Along the line of action: delta_n = delta_x cos(alpha), per F_bt / b.
  const double c = std::cos(L.pressure_angle);
  sc["mesh_compliance"] =
      compliance_split(final_state, std::abs(te_mean) * c, L.load_N / c / (1e3 * L.face_width_m));
}

// The static check's Hertz peak pressure on tooth 0 (history
// contact_pressure_t0_Pa, last row) against ISO 6336-2.
void add_static_contact_pressure(nlohmann::json& sc, const GearLayout& L, const History& h) {
  const double hertz =
      h.at(h.rows() - 1, static_cast<std::size_t>(h.index("contact_pressure_t0_Pa")));
  // ISO 6336-2's nominal contact stress for tooth 0's load alone (one
  // pair: Z_eps = 1), Z_beta = 1 (spur), u -> infinity (rack).
  const double iso_h =
      gear::iso_sigma_H0(sc.at("tooth0_force_N").get<double>() * std::cos(L.pressure_angle),
                         2.0 * L.pitch_radius, L.face_width_m, L.pressure_angle, L.contact_modulus);
  sc["hertz_peak_pressure_Pa"] = hertz;
  sc["iso_sigma_H0_Pa"] = iso_h;
  sc["hertz_peak_pressure_note"] =
      "Hertz line contact on tooth 0's resolved force and its involute's curvature where the "
      "force acts (a sub-model, not read from particles); ISO's sigma_H0 is the same at the "
      "pitch point";
}

// The pressure on the rack's flank around a resolved contact
// (scene.resolve_contact), from its outline particles within four
// half-widths of tooth 0's contact: each one's contact force along the
// flank's normal over its share of the flank, halfway to its neighbours.
struct FlankPressure {
  std::vector<double> s, p;  // position along the flank [m], pressure [Pa]
  double load = 0.0;         // the row's force per unit face width [N/m]
  double centre = 0.0;       // the force's centroid [m]
  double peak = 0.0;         // the largest single-particle pressure [Pa]
};
FlankPressure resolved_flank_pressure(const GearLayout& L, const Simulation& final_state) {
  const Particles& q = final_state.particles;
  const Body& rack = final_state.bodies[1];
  const GearLayout::ResolvedContact& c = L.resolved;
  const double window = std::max(4.0 * c.half_width, 12.0 * c.spacing);
  // The flank's outward normal where it is loaded (reference: the rack's
  // displacement is microns) and the tangent along which s runs.
  const double nx = c.ty, ny = -c.tx;
  std::vector<std::pair<double, double>> row;  // (s, force)
  double outward = 0.0;
  for (std::size_t i = rack.begin; i < rack.end; ++i) {
    if (!std::isfinite(q.surf_depth[i])) continue;
    const double dx = q.x0[i] - c.x, dy = q.y0[i] - c.y;
    const double s = dx * c.tx + dy * c.ty;
    if (std::abs(s) > window || std::abs(dx * nx + dy * ny) > c.spacing) continue;
    outward += q.surf_nx[i] * nx + q.surf_ny[i] * ny;
    row.push_back({s, q.mass[i] * (q.contact_ax[i] * nx + q.contact_ay[i] * ny)});
  }
  FlankPressure out;
  if (row.size() < 3) return out;
  // A contact force pushes into the body, against its outward normal.
  const double into = outward > 0.0 ? -1.0 : 1.0;
  std::sort(row.begin(), row.end());
  double moment = 0.0;
  for (std::size_t k = 0; k < row.size(); ++k) {
    const double left = k > 0 ? row[k].first - row[k - 1].first : row[k + 1].first - row[k].first;
    const double right = k + 1 < row.size() ? row[k + 1].first - row[k].first : left;
    const double force = into * row[k].second;
    out.s.push_back(row[k].first);
    out.p.push_back(force / (0.5 * (left + right)));
    out.load += force;
    moment += force * row[k].first;
    out.peak = std::max(out.peak, out.p.back());
  }
  out.centre = out.load > 0.0 ? moment / out.load : 0.0;
  return out;
}

// A resolved static contact: the flank's pressure fitted with the Hertz
// ellipse about its centroid, against the Hertz sub-model on the same tooth
// force (hertz_peak_pressure_Pa) and that ellipse's half-width 2 F' / (pi p0).
void add_resolved_contact_pressure(nlohmann::json& sc, const GearLayout& L,
                                   const Simulation& final_state) {
  const FlankPressure f = resolved_flank_pressure(L, final_state);
  if (f.s.empty()) return;
  const diagnostics::HertzEllipseFit fit =
      diagnostics::fit_hertz_ellipse(f.s, f.p, L.resolved.half_width, f.centre);
  const double hertz = sc.at("hertz_peak_pressure_Pa").get<double>();
  const double line_load = sc.at("tooth0_force_N").get<double>() / L.face_width_m;
  const double a_hertz = hertz > 0.0 ? 2.0 * line_load / (std::numbers::pi * hertz) : 0.0;
  nlohmann::json profile = nlohmann::json::array();
  for (std::size_t k = 0; k < f.s.size(); ++k) {
    if (f.p[k] > 0.0) profile.push_back({f.s[k] - f.centre, f.p[k]});
  }
  sc["resolved_peak_pressure_Pa"] = fit.p0;
  sc["resolved_peak_pressure_error_vs_hertz"] = hertz > 0.0 ? fit.p0 / hertz - 1.0 : 0.0;
  sc["resolved_half_width_m"] = fit.a;
  sc["resolved_half_width_error_vs_hertz"] = a_hertz > 0.0 ? fit.a / a_hertz - 1.0 : 0.0;
  sc["resolved_max_particle_pressure_Pa"] = f.peak;
  sc["resolved_fit_rms_Pa"] = fit.rms;
  sc["resolved_load_fraction"] = f.load / line_load;
  sc["resolved_contact_spacing_m"] = L.resolved.spacing;
  sc["resolved_particles_across_half_width"] = fit.a / L.resolved.spacing;
  sc["resolved_pressure_profile_s_m_p_Pa"] = profile;
  sc["resolved_pressure_note"] =
      "read from the rack's outline particles at tooth 0's contact (their contact forces over "
      "their shares of the flank), fitted with the Hertz ellipse; hertz_peak_pressure_Pa is "
      "the sub-model on the same tooth force";
}

// The largest Hertz contact pressure of any modelled tooth over the run
// (a sub-model on the resolved tooth force, history contact_pressure_t<k>_Pa).
struct PeakPressure {
  double pressure_Pa = 0.0, time_s = 0.0;
  int tooth = 0;
};
PeakPressure peak_contact_pressure(const GearLayout& L, const History& h,
                                   const std::vector<double>& t) {
  PeakPressure peak;
  for (int k : L.pinion_teeth) {
    const long col = h.index("contact_pressure_t" + std::to_string(k) + "_Pa");
    if (col < 0) continue;
    for (std::size_t row = 0; row < h.rows(); ++row) {
      const double v = h.at(row, static_cast<std::size_t>(col));
      if (v > peak.pressure_Pa) {
        peak.pressure_Pa = v;
        peak.time_s = t[row];
        peak.tooth = k;
      }
    }
  }
  return peak;
}

// Linear elasticity under a load at a fixed point gives a fillet peak per
// unit load that does not depend on the load. The check reports its own:
// the tension peak per unit tooth-0 force when tooth 0 first carries half
// its final force (in the load ramp, where the tooth, much stiffer than the
// mesh mode the ramp is slow against, follows its force quasi-statically:
// at the HPSTC the ratio along a 7 kN ramp stays within 0.2 % of the
// final), against the final one, with the nominal root bending likewise:
// where both change, the load's line moved, not the fillet's reading.
nlohmann::json static_linearity(const History& h) {
  const std::vector<double> force = h.column("tooth_force_t0_N");
  const std::vector<double> peak = h.column("fillet_tension_peak_t0_Pa");
  const std::vector<double> bending = h.column("root_bending_t0_Pa");
  if (force.empty() || !(force.back() > 0.0)) return nullptr;
  const double final_force = force.back();
  std::size_t k = 0;
  while (k + 1 < force.size() && force[k] < 0.5 * final_force) ++k;
  if (!(force[k] > 0.0)) return nullptr;
  const double per_n_half = peak[k] / force[k], per_n_final = peak.back() / final_force;
  const double bending_half = bending[k] / force[k], bending_final = bending.back() / final_force;
  return {{"half_load_tooth0_force_N", force[k]},
          {"half_load_time_s", h.at(k, static_cast<std::size_t>(h.index("time_s")))},
          {"fillet_tension_peak_per_N_at_half_load_Pa_per_N", per_n_half},
          {"fillet_tension_peak_per_N_at_final_load_Pa_per_N", per_n_final},
          {"fillet_tension_peak_per_N_change", per_n_final / per_n_half - 1.0},
          {"nominal_bending_per_N_change", bending_final / bending_half - 1.0},
          {"note",
           "change = (per N at the final load) / (per N at half of it) - 1; the half-load state "
           "is read in the load ramp"}};
}

// A run whose materials carry strength but whose pair ISO 6336 method B
// cannot rate (rack_pinion.cpp, rating_document_of) says why.
void say_why_not_rated(nlohmann::json& a, const GearLayout& L) {
  if (L.rating_refusal.is_null()) return;
  a["rating"] = {{"status", "not_rated"},
                 {"reason", L.rating_refusal.at("message")},
                 {"pointer", L.rating_refusal.at("pointer")}};
  a["warnings"].push_back("rating: not rated, " +
                          L.rating_refusal.at("message").get<std::string>());
}

// A static check answers for tooth 0 loaded alone. Where it carries less
// than half the rack's load, the load went elsewhere (other rack teeth
// meeting its neighbours, or none meeting its driving flank: a rack count of
// one once put the rack tooth beside the other flank, and the check read
// zero everywhere without a word): the run says so.
void warn_of_an_unloaded_tooth0(nlohmann::json& a, const nlohmann::json& sc, const GearLayout& L) {
  const double share = sc.at("load_carried_by_tooth0").get<double>();
  // More than the load: the rack tooth is wedged between two pinion teeth
  // (both its flanks touch, as a mesh without backlash can), and tooth 0's
  // force is the load plus the wedge's. Measured on the accuracy map
  // (docs/validation.md): shares of 1.15-1.50 read the fillet 11-38 % away
  // from the FE of one loaded flank.
  if (share > 1.05) {
    char text[400];
    std::snprintf(text, sizeof text,
                  "static check: tooth 0 carries %.0f %% of the rack load: the rack tooth is "
                  "wedged between pinion teeth (both flanks in contact; give "
                  "/scene/pinion/backlash_mm some play), so its fillet numbers are not those of "
                  "the single loaded flank the check rates",
                  100.0 * share);
    a["warnings"].push_back(text);
    return;
  }
  if (share >= 0.5) return;
  char text[320];
  std::snprintf(text, sizeof text,
                "static check: tooth 0 carries %.0f %% of the rack load (%.4g N of %.4g N "
                "tangential): its fillet numbers are not those of the single loaded pair the "
                "check rates (the load went through other teeth, or had not reached tooth 0 "
                "when the run ended)",
                100.0 * share, share * L.load_N, L.load_N);
  a["warnings"].push_back(text);
}

}  // namespace

nlohmann::json analyse_rack_pinion(const GearLayout& L, const History& h,
                                   const Simulation& final_state) {
  nlohmann::json a;
  const std::vector<double> t = h.column("time_s");
  const double t_stable = velocity_stability_time(t, h.column("rack_vx_m_s"), 0.05);
  a["velocity_stability"] = velocity_stability(h, t, t_stable);
  const std::vector<double> fc = h.column("contact_force_N");
  const double f_max = max_of(fc);
  const std::size_t k_max = last_index_of(fc, f_max);
  add_root_stresses(a, L, h, f_max);
  a["contact_ratio"] = measured_contact_ratio(L, h, fc, f_max);
  const double te_mean = add_transmission_error(a, L, h, t);

  // A static check: tooth 0 modelled, loaded and relaxed.
  const auto t0 = std::find(L.pinion_teeth.begin(), L.pinion_teeth.end(), 0);
  if (L.quasi_static && L.load_N > 0 && h.rows() > 0 && t0 != L.pinion_teeth.end()) {
    const auto i0 = static_cast<std::size_t>(t0 - L.pinion_teeth.begin());
    nlohmann::json sc = static_root_check(L, h, final_state, i0);
    if (a.contains("mesh_stiffness_N_per_mm_um")) {
      add_static_mesh_stiffness(sc, a["mesh_stiffness_N_per_mm_um"].get<double>(), L, final_state,
                                te_mean);
    }
    add_static_contact_pressure(sc, L, h);
    if (L.resolved.spacing > 0.0) add_resolved_contact_pressure(sc, L, final_state);
    warn_of_an_unloaded_tooth0(a, sc, L);
    sc["linearity"] = static_linearity(h);
    a["static_check"] = sc;
    if (!L.rating_document.is_null()) {
      a["rating"] = gear::iso6336::rating_from_static_check(L.rating_document, sc);
    } else {
      say_why_not_rated(a, L);
    }
  }

  // A loaded dynamic run: its steady mesh and the lumped model beside it.
  if (!L.quasi_static && (L.load_N > 0 || L.torque_Nm) && h.rows() > 1) {
    a["dynamics"] = analyse_mesh_dynamics(L, h);
    if (!L.rating_document.is_null()) {
      a["rating"] = gear::iso6336::rating_from_dynamics(L.rating_document, a["dynamics"]);
    } else {
      say_why_not_rated(a, L);
    }
  }

  const PeakPressure p = peak_contact_pressure(L, h, t);
  a["summary_fields"] = {
      {"max_contact_pressure_Pa", p.pressure_Pa},
      {"max_contact_pressure_tooth", p.tooth},
      {"max_contact_pressure_time_s", p.time_s},
      {"velocity_stability_time_s", t_stable},
      {"max_contact_force_N", f_max},
      {"max_contact_force_time_s", t.empty() ? 0.0 : t[k_max]},
      {"max_root_stress_Pa", a["max_root_stress_Pa"].get<double>()},
      {"modelled_teeth",
       {{"pinion", L.pinion_teeth}, {"rack", L.rack_teeth.size()}, {"reason", L.selection}}}};
  return a;
}

}  // namespace gearsph::scenes
