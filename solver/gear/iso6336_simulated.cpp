#include "solver/gear/iso6336_simulated.hpp"

#include <cmath>
#include <numbers>

#include "solver/gear/iso6336_error.hpp"
#include "solver/gear/iso6336_materials.hpp"
#include "solver/gear/iso6336_rating.hpp"

namespace gearsph::gear::iso6336 {

namespace {

using json = nlohmann::json;
constexpr double kPi = std::numbers::pi;

// The material of the rating schema: the job's, without anything else.
json strength_material(const json& m) {
  json out = json::object();
  for (const char* key :
       {"E_Pa", "nu", "rho_kg_m3", "iso6336_5", "sigma_Hlim_Pa", "sigma_Flim_Pa", "yield_Pa"}) {
    if (m.contains(key)) out[key] = m.at(key);
  }
  return out;
}

}  // namespace

nlohmann::json rack_pinion_rating_document(const geometry::PinionGeometry& pinion,
                                           double face_width_m, const json& pm, const json& rm,
                                           double load_N, double omega, const json& options) {
  if (!has_strength(pm) || !has_strength(rm) || load_N <= 0.0) return nullptr;
  const geometry::BasicRack& tool = pinion.spec().tool;
  const double m = tool.module_m;
  double speed_rpm = options.value("speed_rpm", std::abs(omega) * 30.0 / kPi);
  if (speed_rpm <= 0.0) {
    throw InvalidRating("/load/speed_rpm",
                        "a held pinion has no speed for K_v: give the service speed_rpm");
  }
  json load = {{"tangential_force_N", load_N},
               {"speed_rpm", speed_rpm},
               {"application_factor", options.value("application_factor", 1.0)},
               {"life_h", options.value("life_h", 20000.0)}};
  return {
      {"name", "rack_pinion static check"},
      {"pair",
       {{"type", "rack"},
        {"normal_module_mm", m * 1e3},
        {"pressure_angle_deg", tool.pressure_angle_rad * 180.0 / kPi},
        {"face_width_mm", face_width_m * 1e3},
        {"basic_rack",
         {{"addendum_coef", tool.addendum() / m},
          {"dedendum_coef", tool.dedendum() / m},
          {"root_radius_coef", tool.root_radius() / m}}}}},
      {"gears",
       {{{"teeth", pinion.teeth()},
         {"profile_shift", pinion.spec().profile_shift},
         {"tip_diameter_mm", 2e3 * pinion.tip_radius()},
         {"form_diameter_mm", 2e3 * pinion.form_radius()},
         {"material", strength_material(pm)}},
        {{"material", strength_material(rm)}}}},
      {"load", load},
      {"required_safety",
       {{"S_H", options.value("required_S_H", 1.0)}, {"S_F", options.value("required_S_F", 1.4)}}}};
}

namespace {

// A fillet tension peak and a contact pressure, each for tooth 0's force,
// rated under method B's factors: scaled to all of F_t on the one tooth
// (`scale` = F_t over tooth 0's tangential force; the fillet stress is
// linear in the load, the Hertz pressure goes with its square root), times
// Y_beta Y_B Y_DT and K_A K_v K_Fbeta K_Falpha (bending) or the square root
// of K_A K_v K_Hbeta K_Halpha (contact), against method B's permissible
// stresses of the pinion.
struct RatedStresses {
  double sigma_F, S_F, sigma_H, S_H;
};

double bending_factors(const json& f) {
  return f.at("K_A").get<double>() * f.at("K_v").get<double>() * f.at("K_Fbeta").get<double>() *
         f.at("K_Falpha").get<double>() * f.at("Y_beta").get<double>() *
         f.at("Y_B")[0].get<double>() * f.at("Y_DT").get<double>();
}

double contact_factors(const json& f) {
  return f.at("K_A").get<double>() * f.at("K_v").get<double>() * f.at("K_Hbeta").get<double>() *
         f.at("K_Halpha").get<double>();
}

RatedStresses rate_stresses(const json& b, double scale, double fillet_peak_Pa,
                            double pressure_Pa) {
  const json& f = b.at("factors");
  RatedStresses r{};
  r.sigma_F = fillet_peak_Pa * scale * bending_factors(f);
  r.S_F = b.at("bending").at("sigma_FG_Pa")[0].get<double>() / r.sigma_F;
  r.sigma_H = pressure_Pa * std::sqrt(scale * contact_factors(f));
  r.S_H = b.at("pitting").at("sigma_HG_Pa")[0].get<double>() / r.sigma_H;
  return r;
}

}  // namespace

nlohmann::json rating_from_static_check(const json& document, const json& sc) {
  const json b = rate_document(document);
  const double F_t = document.at("load").at("tangential_force_N").get<double>();
  const double alpha = document.at("pair").at("pressure_angle_deg").get<double>() * kPi / 180.0;
  // Tooth 0's tangential share, and the simulated stresses scaled to all of
  // F_t on the one tooth (method B's single pair at its load point).
  const double ft0 = sc.at("tooth0_force_N").get<double>() * std::cos(alpha);
  const double scale = F_t / ft0;
  const RatedStresses sim_r = rate_stresses(b, scale, sc.at("fillet_tension_peak_Pa").get<double>(),
                                            sc.at("hertz_peak_pressure_Pa").get<double>());
  // Method B with Y_F Y_S at the check's own load point, for the same load.
  const double sigma_F_load_point =
      sc.at("iso_sigma_F0_Pa").get<double>() * scale * bending_factors(b.at("factors"));
  const json& G_F = b.at("bending").at("sigma_FG_Pa");
  const json& G_H = b.at("pitting").at("sigma_HG_Pa");
  const double req_F = b.at("bending").at("required_S_F").get<double>();
  const double req_H = b.at("pitting").at("required_S_H").get<double>();
  json sim = {{"sigma_F_Pa", sim_r.sigma_F},
              {"S_F", sim_r.S_F},
              {"sigma_H_hertz_Pa", sim_r.sigma_H},
              {"S_H_hertz", sim_r.S_H}};
  double S_H_sim = sim_r.S_H;
  if (sc.contains("resolved_peak_pressure_Pa")) {
    const double resolved = sc.at("resolved_peak_pressure_Pa").get<double>() *
                            std::sqrt(scale * contact_factors(b.at("factors")));
    sim["sigma_H_resolved_Pa"] = resolved;
    sim["S_H_resolved"] = G_H[0].get<double>() / resolved;
    S_H_sim = G_H[0].get<double>() / resolved;
  }
  const double yield = document.at("gears")[0].at("material").value("yield_Pa", 0.0);
  const double static_F = b.at("static").at("tangential_force_N").get<double>();
  if (yield > 0.0) {
    sim["S_yield"] = yield / (sc.at("fillet_tension_peak_Pa").get<double>() * static_F / ft0);
  }
  const bool bending_governs = sim["S_F"].get<double>() / req_F < S_H_sim / req_H;
  return {{"note",
           "S_F: the fillet's recovered tension peak in place of F_t/(b m_n) Y_F Y_S, method B's "
           "at its outer point of single contact and at the check's load point; S_H: Hertz on "
           "tooth 0's simulated force at the load point (resolved: the particles' own pressure), "
           "method B's at the inner point of single contact (Z_B): compare S_H at contact_point "
           "lpstc"},
          {"load_point", sc.at("contact_point")},
          {"tooth0_share", ft0 / F_t},
          {"simulated", sim},
          {"method_B",
           {{"sigma_F_Pa", b.at("bending").at("sigma_F_Pa")[0]},
            {"S_F", b.at("bending").at("S_F")[0]},
            {"sigma_F_at_load_point_Pa", sigma_F_load_point},
            {"S_F_at_load_point", G_F[0].get<double>() / sigma_F_load_point},
            {"sigma_H_Pa", b.at("pitting").at("sigma_H_Pa")[0]},
            {"S_H", b.at("pitting").at("S_H")[0]}}},
          {"required_S_F", req_F},
          {"required_S_H", req_H},
          {"governing",
           {{"mode", bending_governs ? "root bending of the pinion" : "pitting of the pinion"},
            {"margin", bending_governs ? sim["S_F"].get<double>() / req_F : S_H_sim / req_H}}},
          {"iso6336", b}};
}

nlohmann::json rating_from_dynamics(const json& document, const json& dyn) {
  const json b = rate_document(document);
  const double K_v_iso = b.at("factors").at("K_v").get<double>();
  const double req_F = b.at("bending").at("required_S_F").get<double>();
  const double req_H = b.at("pitting").at("required_S_H").get<double>();
  const double S_F = b.at("bending").at("S_F")[0].get<double>();
  const double S_H = b.at("pitting").at("S_H")[0].get<double>();
  json kv = {{"iso6336_1_method_B", K_v_iso},
             {"measured", nullptr},
             {"measured_from",
              "the run's steady mesh (analysis.dynamics): peak over mean mesh force over its "
              "whole steady mesh periods"}};
  json out = {{"note",
               "a dynamic run: ISO 6336 method B for the job's pinion, rack, materials, load and "
               "speed, with K_v as ISO's method B gives it and as the run measured it; "
               "with_measured_K_v rates method B's stresses again with the measured K_v in place "
               "of ISO's (sigma_F in proportion, sigma_H with its square root; K_Falpha and "
               "K_Halpha kept at method B's)"},
              {"method_B",
               {{"sigma_F_Pa", b.at("bending").at("sigma_F_Pa")[0]},
                {"S_F", S_F},
                {"sigma_H_Pa", b.at("pitting").at("sigma_H_Pa")[0]},
                {"S_H", S_H}}},
              {"required_S_F", req_F},
              {"required_S_H", req_H}};
  double S_F_gov = S_F, S_H_gov = S_H;
  if (dyn.value("steady", false) && dyn.value("K_v", 0.0) > 0.0) {
    const double K_v = dyn.at("K_v").get<double>();
    kv["measured"] = K_v;
    kv["steady_from_s"] = dyn.at("steady_from_s");
    kv["steady_periods"] = dyn.at("steady_periods");
    S_F_gov = S_F * K_v_iso / K_v;
    S_H_gov = S_H * std::sqrt(K_v_iso / K_v);
    const double ratio = K_v / K_v_iso;
    kv["ratio_measured_over_iso"] = ratio;
    out["with_measured_K_v"] = {
        {"sigma_F_Pa", b.at("bending").at("sigma_F_Pa")[0].get<double>() * ratio},
        {"S_F", S_F_gov},
        {"sigma_H_Pa", b.at("pitting").at("sigma_H_Pa")[0].get<double>() * std::sqrt(ratio)},
        {"S_H", S_H_gov}};
  } else {
    const std::string note = dyn.value("note", std::string());
    kv["reason"] = note.empty() ? "the run did not reach a steady mesh" : note;
  }
  out["K_v"] = kv;
  const bool bending_governs = S_F_gov / req_F < S_H_gov / req_H;
  out["governing"] = {
      {"mode", bending_governs ? "root bending of the pinion" : "pitting of the pinion"},
      {"margin", bending_governs ? S_F_gov / req_F : S_H_gov / req_H},
      {"with", kv["measured"].is_null() ? "method B's K_v" : "the measured K_v"}};
  out["iso6336"] = b;
  return out;
}

nlohmann::json rating_from_fe_check(const json& rating, const json& fe) {
  const json& b = rating.at("iso6336");
  const double F_t = b.at("load").at("F_t_N").get<double>();
  const json& load = fe.at("load");
  const double scale = F_t / load.at("tangential_force_N").get<double>();
  const RatedStresses r = rate_stresses(b, scale, fe.at("fillet_tension_peak_Pa").get<double>(),
                                        load.at("hertz_peak_pressure_Pa").get<double>());
  const json& sim = rating.at("simulated");
  const double S_F_sim = sim.at("S_F").get<double>(), S_H_sim = sim.at("S_H_hertz").get<double>();
  return {{"note",
           "the FE check's fillet tension peak and its Hertz patch's peak pressure (for the FE "
           "load on tooth 0, scaled to all of F_t on it) under the same factors and permissible "
           "stresses as analysis.rating.simulated; difference = simulated / FE - 1"},
          {"tooth0_force_N", load.at("normal_force_N")},
          {"load_radius_m", load.at("load_radius_m")},
          {"fillet_tension_peak_Pa", fe.at("fillet_tension_peak_Pa")},
          {"hertz_peak_pressure_Pa", load.at("hertz_peak_pressure_Pa")},
          {"sigma_F_Pa", r.sigma_F},
          {"S_F", r.S_F},
          {"sigma_H_hertz_Pa", r.sigma_H},
          {"S_H_hertz", r.S_H},
          {"S_F_simulated", S_F_sim},
          {"S_H_hertz_simulated", S_H_sim},
          {"S_F_difference", S_F_sim / r.S_F - 1.0},
          {"S_H_difference", S_H_sim / r.S_H - 1.0}};
}

}  // namespace gearsph::gear::iso6336
