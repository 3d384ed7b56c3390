#include "fe/gear_fe_job.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>

#include "solver/gear/gear_rating.hpp"
#include "solver/job/job.hpp"
#include "solver/scene/rack_pinion.hpp"

namespace gearsph::fe {

namespace {

[[noreturn]] void refuse(const std::string& pointer, const std::string& message) {
  throw InvalidJob({{pointer, message}});
}

}  // namespace

double contact_radius(const geometry::PinionGeometry& pinion, const nlohmann::json& point) {
  if (point.is_number()) return 1e-3 * point.get<double>();
  return gear::path_point_radius(pinion, gear::rack_contact_path(pinion), point.get<std::string>());
}

GearFeJob read_gear_fe_job(const nlohmann::json& job) {
  const nlohmann::json& s = job.at("scene");
  if (s.at("type") != "rack_pinion") {
    refuse("/scene/type", "the FE check models the rack_pinion scene's pinion");
  }
  if (!s.at("quasi_static").get<bool>()) {
    refuse("/scene/quasi_static",
           "the FE check solves the static problem: it needs a quasi-static job");
  }
  const nlohmann::json& pj = s.at("pinion");
  const nlohmann::json& rj = s.at("rack");
  GearFeJob out;
  out.name = job.value("name", "job");
  out.rack_load_N = rj.at("load_N").get<double>();
  if (!(out.rack_load_N > 0.0)) {
    refuse("/scene/rack/load_N", "the FE check needs a load: give the rack load (per gear)");
  }
  // The pinion exactly as build_rack_pinion generates it.
  geometry::BasicRack tool;
  tool.module_m = 1e-3 * pj.at("module_mm").get<double>();
  tool.pressure_angle_rad = pj.at("pressure_angle_deg").get<double>() * std::numbers::pi / 180.0;
  tool.addendum_coef = pj.at("addendum_coef").get<double>();
  tool.dedendum_coef = pj.at("dedendum_coef").get<double>();
  GearFeCase& c = out.model;
  c.pinion.teeth = pj.at("teeth").get<int>();
  c.pinion.profile_shift = pj.at("profile_shift").get<double>();
  c.pinion.backlash_m = 1e-3 * pj.at("backlash_mm").get<double>();
  // The SPH scene's rule (rack_pinion.cpp): given, or ISO 53's where it
  // fits both the pinion's and the rack's tooth space.
  const double rack_backlash_m = 1e-3 * rj.value("backlash_mm", 0.0);
  tool.root_radius_coef =
      pj.contains("cutter_tip_radius_coef")
          ? pj.at("cutter_tip_radius_coef").get<double>()
          : tool.default_root_radius_coef(std::min(c.pinion.backlash_m, rack_backlash_m));
  c.pinion.tool = tool;
  out.module_m = tool.module_m;
  out.pressure_angle = tool.pressure_angle_rad;
  std::optional<geometry::PinionGeometry> pinion;
  try {
    pinion.emplace(c.pinion);
  } catch (const std::invalid_argument& e) {
    refuse("/scene/pinion", std::string("cannot generate this pinion: ") + e.what());
  }
  const nlohmann::json& pm =
      s.contains("pinion_material") ? s.at("pinion_material") : s.at("material");
  const nlohmann::json& rm = s.contains("rack_material") ? s.at("rack_material") : s.at("material");
  c.E_Pa = pm.at("E_Pa").get<double>();
  c.nu = pm.at("nu").get<double>();
  c.rack_E_Pa = rm.at("E_Pa").get<double>();
  c.rack_nu = rm.at("nu").get<double>();
  c.face_width_m = 1e-3 * pj.at("face_width_mm").get<double>();
  // The scene's rack (rack_pinion.cpp, build_rack): two modules of back
  // unless given.
  c.rack_back_m = rj.contains("back_thickness_mm") ? 1e-3 * rj.at("back_thickness_mm").get<double>()
                                                   : 2.0 * c.pinion.tool.module_m;
  c.rack_backlash_m = 1e-3 * rj.at("backlash_mm").get<double>();
  // The teeth the scene's static check models (tooth 0 and at least its
  // neighbours), held where its hub ring begins (rack_pinion.cpp: r_drive).
  const std::vector<int> teeth = scenes::static_check_pinion_teeth(pj);
  c.first_tooth = teeth.front();
  c.last_tooth = teeth.back();
  c.whole_gear = static_cast<int>(teeth.size()) >= c.pinion.teeth;
  out.rim_depth_m = scenes::pinion_rim_depth_m(pj, pinion->tip_radius() - pinion->root_radius());
  c.fixed_radius_m = pinion->root_radius() - out.rim_depth_m;
  if (!(c.fixed_radius_m > 0.0)) {
    refuse("/scene/pinion/rim_depth_mm", "the rim reaches the pinion centre");
  }
  // The driving flank faces the way the pinion turns (clockwise, omega < 0:
  // tooth 0 moves toward -x); a pinion held still (omega 0) is loaded by the
  // rack's resisting force, which pushes along +x unless the rack moves +x.
  const double omega = pj.at("omega_rad_s").get<double>();
  const double rack_v = rj.at("velocity_m_s").get<double>();
  c.flank_side = omega < 0.0 ? -1 : omega > 0.0 ? 1 : (rack_v <= 0.0 ? -1 : 1);
  // Tooth 0 carries the rack load: F_n = F_t / cos(alpha) along the line of action.
  c.normal_force_N = out.rack_load_N / std::cos(out.pressure_angle);
  const nlohmann::json point = s.contains("contact_point") ? s.at("contact_point") : "pitch";
  out.contact_point = point.is_number() ? [&] {
    char text[48];
    std::snprintf(text, sizeof text, "%g mm", point.get<double>());
    return std::string(text);
  }()
                                        : point.get<std::string>();
  c.load_radius_m = contact_radius(*pinion, point);
  if (c.load_radius_m < pinion->form_radius() || c.load_radius_m > pinion->tip_radius()) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "the contact radius %.4g mm is not on the flank (form circle %.4g mm to tip "
                  "circle %.4g mm)",
                  1e3 * c.load_radius_m, 1e3 * pinion->form_radius(), 1e3 * pinion->tip_radius());
    refuse("/scene/contact_point", text);
  }
  return out;
}

}  // namespace gearsph::fe
