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

nlohmann::json rating_from_static_check(const json& document, const json& sc) {
  const json b = rate_document(document);
  const json& f = b.at("factors");
  const double F_t = document.at("load").at("tangential_force_N").get<double>();
  const double alpha = document.at("pair").at("pressure_angle_deg").get<double>() * kPi / 180.0;
  // Tooth 0's tangential share, and the simulated stresses scaled to all of
  // F_t on the one tooth (method B's single pair at its load point).
  const double ft0 = sc.at("tooth0_force_N").get<double>() * std::cos(alpha);
  const double scale = F_t / ft0;
  const double K_F = f.at("K_A").get<double>() * f.at("K_v").get<double>() *
                     f.at("K_Fbeta").get<double>() * f.at("K_Falpha").get<double>();
  const double K_H = f.at("K_A").get<double>() * f.at("K_v").get<double>() *
                     f.at("K_Hbeta").get<double>() * f.at("K_Halpha").get<double>();
  const double Y_other =
      f.at("Y_beta").get<double>() * f.at("Y_B")[0].get<double>() * f.at("Y_DT").get<double>();
  const double sigma_F_sim = sc.at("fillet_tension_peak_Pa").get<double>() * scale * Y_other * K_F;
  // Method B with Y_F Y_S at the check's own load point, for the same load.
  const double sigma_F_load_point = sc.at("iso_sigma_F0_Pa").get<double>() * scale * Y_other * K_F;
  const double hertz = sc.at("hertz_peak_pressure_Pa").get<double>() * std::sqrt(scale * K_H);
  const json& G_F = b.at("bending").at("sigma_FG_Pa");
  const json& G_H = b.at("pitting").at("sigma_HG_Pa");
  const double req_F = b.at("bending").at("required_S_F").get<double>();
  const double req_H = b.at("pitting").at("required_S_H").get<double>();
  json sim = {{"sigma_F_Pa", sigma_F_sim},
              {"S_F", G_F[0].get<double>() / sigma_F_sim},
              {"sigma_H_hertz_Pa", hertz},
              {"S_H_hertz", G_H[0].get<double>() / hertz}};
  double S_H_sim = G_H[0].get<double>() / hertz;
  if (sc.contains("resolved_peak_pressure_Pa")) {
    const double resolved =
        sc.at("resolved_peak_pressure_Pa").get<double>() * std::sqrt(scale * K_H);
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

}  // namespace gearsph::gear::iso6336
