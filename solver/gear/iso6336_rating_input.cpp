// The rating document to RatingInput: schema check (valijson through
// solver/core/json_schema), defaults, and the rules the schema cannot say.
#include <cmath>
#include <numbers>

#include "solver/core/json_schema.hpp"
#include "solver/gear/iso6336_rating.hpp"

namespace gearsph {
extern const char* const kRatingSchemaText;
}

namespace gearsph::gear::iso6336 {

namespace {

using json = nlohmann::json;
constexpr double kMm = 1e-3;
constexpr double kDeg = std::numbers::pi / 180.0;

const jsonschema::Validator& validator() {
  static const jsonschema::Validator v(rating_schema());
  return v;
}

json checked(const json& document) {
  const std::vector<jsonschema::Error> errors = validator().validate(document);
  if (!errors.empty()) {
    std::vector<RatingIssue> issues;
    for (const auto& e : errors) issues.push_back({e.pointer, e.message});
    throw InvalidRating(std::move(issues));
  }
  return validator().apply_defaults(document);
}

// Exactly one of two keys of `object` at `pointer`; its value, scaled.
double one_of(const json& object, const std::string& pointer, const char* a, const char* b,
              bool required) {
  if (object.contains(a) && object.contains(b)) {
    throw InvalidRating(pointer + "/" + b, std::string("give ") + a + " or " + b + ", not both");
  }
  if (object.contains(a)) return object.at(a).get<double>();
  if (object.contains(b)) return object.at(b).get<double>();
  if (required) throw InvalidRating(pointer, std::string("needs ") + a + " or " + b);
  return 0.0;
}

void read_pair(const json& p, RatingInput& in) {
  PairSpec& s = in.pair;
  s.rack = p.at("type").get<std::string>() == "rack";
  s.m_n = p.at("normal_module_mm").get<double>() * kMm;
  s.alpha_n = p.at("pressure_angle_deg").get<double>() * kDeg;
  s.beta = p.at("helix_angle_deg").get<double>() * kDeg;
  s.b = p.at("face_width_mm").get<double>() * kMm;
  if (p.contains("center_distance_mm")) {
    if (s.rack) {
      throw InvalidRating("/pair/center_distance_mm", "has no meaning for a rack: leave it out");
    }
    s.a_w = p.at("center_distance_mm").get<double>() * kMm;
  }
  const json& r = p.at("basic_rack");
  s.tool.h_aP = r.at("addendum_coef").get<double>();
  s.tool.h_fP = r.at("dedendum_coef").get<double>();
  s.tool.rho_fP = r.at("root_radius_coef").get<double>();
  s.tool.s_pr = r.at("protuberance_residual_coef").get<double>();
  in.accuracy_grade = p.at("accuracy_grade").get<int>();
  in.K_Hbeta_given = p.value("K_Hbeta", 0.0);
  in.F_betax_um = p.value("F_betax_um", 0.0);
  if (in.K_Hbeta_given > 0.0 && in.F_betax_um > 0.0) {
    throw InvalidRating("/pair/F_betax_um", "give K_Hbeta or F_betax_um, not both");
  }
}

void read_gear(const json& gear, int k, RatingInput& in) {
  const std::string at = "/gears/" + std::to_string(k);
  PairSpec& s = in.pair;
  const bool rack = s.rack && k == 1;
  if (rack) {
    for (const char* key : {"teeth", "tip_diameter_mm", "form_diameter_mm", "rim_thickness_mm"}) {
      if (gear.contains(key)) {
        throw InvalidRating(at + "/" + key, "has no meaning for the rack: leave it out");
      }
    }
    s.z[k] = kRackTeeth;
  } else {
    if (!gear.contains("teeth")) throw InvalidRating(at, "needs teeth");
    s.z[k] = gear.at("teeth").get<int>();
    s.d_a[k] = gear.value("tip_diameter_mm", 0.0) * kMm;
    s.d_Nf[k] = gear.value("form_diameter_mm", 0.0) * kMm;
    in.rim_m[k] = gear.value("rim_thickness_mm", 0.0) * kMm;
  }
  s.x[k] = gear.at("profile_shift").get<double>();
  if (rack && s.x[k] != 0.0) {
    throw InvalidRating(at + "/profile_shift", "of a rack is 0: shift the pinion instead");
  }
  in.flank_Rz_um[k] = gear.at("flank_Rz_um").get<double>();
  in.root_Rz_um[k] = gear.at("root_Rz_um").get<double>();
  in.mat[k] = read_gear_material(gear.at("material"), at + "/material");
}

// Deviations given, or from the ISO 1328-1 grade at the larger gear's
// diameter (the pinion's for a rack); C_a from C_ay of ISO 6336-1:2006
// (running-in of unmodified profiles) with the pair's mean sigma_Hlim.
void read_deviations(const json& p, RatingInput& in) {
  const PairSpec& s = in.pair;
  std::array<GradeTolerances, 2> t;
  for (int k = 0; k < 2; ++k) {
    const int z = s.rack ? s.z[0] : s.z[k];
    const double d_mm = z * s.m_n / std::cos(s.beta) / kMm;
    t[k] = grade_tolerances(in.accuracy_grade, s.m_n / kMm, d_mm, s.b / kMm);
  }
  in.dev.f_pb_um =
      p.contains("f_pb_um") ? p.at("f_pb_um").get<double>() : std::max(t[0].f_pt_um, t[1].f_pt_um);
  in.dev.f_falpha_um = p.contains("f_falpha_um") ? p.at("f_falpha_um").get<double>()
                                                 : std::max(t[0].f_falpha_um, t[1].f_falpha_um);
  in.dev.f_Hbeta_um = {t[0].f_Hbeta_um, t[1].f_Hbeta_um};
  double c_ay = 0.0;
  for (const GearMaterial& m : in.mat) {
    c_ay += 0.5 * ((1.0 / 18.0) * std::pow(m.sigma_Hlim_Pa / 1e6 / 97.0 - 18.45, 2) + 1.5);
  }
  in.dev.C_a_um = p.contains("tip_relief_um") ? p.at("tip_relief_um").get<double>() : c_ay;
}

void read_load(const json& l, RatingInput& in) {
  const double d1 = in.pair.z[0] * in.pair.m_n / std::cos(in.pair.beta);
  const double torque = one_of(l, "/load", "torque_N_m", "tangential_force_N", true);
  in.F_t_N = l.contains("torque_N_m") ? 2.0 * torque / d1 : torque;
  in.K_A = l.at("application_factor").get<double>();
  const double st = one_of(l, "/load", "static_torque_N_m", "static_tangential_force_N", false);
  in.F_static_N = st <= 0.0                         ? in.K_A * in.F_t_N
                  : l.contains("static_torque_N_m") ? 2.0 * st / d1
                                                    : st;
  in.n1_rpm = l.at("speed_rpm").get<double>();
  in.life_h = l.at("life_h").get<double>();
  if (l.contains("cycles")) {
    in.cycles = {l.at("cycles")[0].get<double>(), l.at("cycles")[1].get<double>()};
  } else {
    in.cycles[0] = 60.0 * in.n1_rpm * in.life_h;
    // A rack tooth: as many as a pinion tooth (the rack's stroke is not known).
    in.cycles[1] = in.pair.rack ? in.cycles[0] : in.cycles[0] * in.pair.z[0] / in.pair.z[1];
  }
}

}  // namespace

const nlohmann::json& rating_schema() {
  static const json schema = json::parse(kRatingSchemaText);
  return schema;
}

RatingInput read_rating(const nlohmann::json& document) {
  const json full = checked(document);
  RatingInput in;
  in.name = full.at("name").get<std::string>();
  read_pair(full.at("pair"), in);
  for (int k = 0; k < 2; ++k) read_gear(full.at("gears")[k], k, in);
  read_deviations(full.at("pair"), in);
  read_load(full.at("load"), in);
  in.nu40_mm2_s = full.at("lubricant").at("nu40_mm2_s").get<double>();
  in.required_S_H = full.at("required_safety").at("S_H").get<double>();
  in.required_S_F = full.at("required_safety").at("S_F").get<double>();
  in.optimum_long_life = full.at("life_factors").at("long_life").get<std::string>() == "optimum";
  in.limited_pitting = full.at("life_factors").at("limited_pitting").get<bool>();
  return in;
}

nlohmann::json rate_document(const nlohmann::json& document) {
  return rate(read_rating(document));
}

}  // namespace gearsph::gear::iso6336
