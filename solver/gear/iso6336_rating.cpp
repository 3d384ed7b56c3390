// The rating itself: ISO 6336-1 load factors, ISO 6336-2 pitting and
// ISO 6336-3 bending of both gears, the static check, the life at the
// required safeties and the governing failure mode, in that order.
#include "solver/gear/iso6336_rating.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "solver/gear/iso6336_bending.hpp"
#include "solver/gear/iso6336_life.hpp"
#include "solver/gear/iso6336_pitting.hpp"

namespace gearsph::gear::iso6336 {

namespace {

using json = nlohmann::json;
constexpr double kPi = std::numbers::pi;

// What both failure modes share: the geometry and the load factors.
struct Mesh {
  PairGeometry g;
  double v_m_s = 0.0, line_load_N_mm = 0.0;
  MeshStiffness c;
  DynamicFactor dyn;
  FaceLoadFactor face;
  TransverseLoadFactor trans;
  double Z_eps = 1.0;
};

// One failure mode of one gear: the stress, its permissible values at the
// static limit and at the reference, and the resulting safeties.
struct ModeResult {
  std::array<double, 2> sigma{}, sigma_static_load{};
  std::array<double, 2> G_static{}, G_ref{}, G{};  // permissible stresses
  std::array<double, 2> S{}, S_static{}, life_factor{};
  std::array<LifeLine, 2> line;
};

Mesh mesh_of(const RatingInput& in) {
  Mesh m;
  m.g = pair_geometry(in.pair);
  m.v_m_s = kPi * m.g.d[0] * in.n1_rpm / 60.0;
  m.line_load_N_mm = in.F_t_N * in.K_A / (in.pair.b * 1e3);
  m.c = mesh_stiffness(m.g, in.mat, m.line_load_N_mm);
  m.dyn = dynamic_factor(m.g, in.mat, m.c, in.dev, in.n1_rpm, m.line_load_N_mm, m.v_m_s);
  const double F_m = in.F_t_N * in.K_A * m.dyn.K_v;
  m.face =
      face_load_factor(m.g, in.mat, m.c, in.dev, F_m, m.v_m_s, in.F_betax_um, in.K_Hbeta_given);
  m.Z_eps = contact_ratio_factor(m.g);
  m.trans = transverse_load_factor(m.g, m.c, in.dev.f_pb_um, m.dyn.y_alpha_um, F_m * m.face.K_Hbeta,
                                   m.Z_eps);
  return m;
}

// The static load over the service load with K_A and K_v: the static check
// keeps the face and transverse load factors of the service load.
double static_ratio(const RatingInput& in, const Mesh& m) {
  return in.F_static_N / (in.F_t_N * in.K_A * m.dyn.K_v);
}

void finish_mode(const RatingInput& in, ModeResult& r, bool optimum, int k) {
  r.G[k] = permissible_stress(r.line[k], r.G_static[k], r.G_ref[k], in.cycles[k], optimum);
  r.S[k] = r.G[k] / r.sigma[k];
  r.S_static[k] = r.G_static[k] / r.sigma_static_load[k];
  r.life_factor[k] = iso6336::life_factor(r.line[k], in.cycles[k], optimum);
}

ModeResult pitting(const RatingInput& in, const Mesh& m, json& factors, json& out) {
  const PairGeometry& g = m.g;
  const double Z_H = zone_factor(g), Z_E = elasticity_factor(in.mat[0], in.mat[1]);
  const double Z_beta = helix_angle_factor(g);
  const std::array<double, 2> Z_BD = single_pair_factors(g);
  const double s_Hlim = std::min(in.mat[0].sigma_Hlim_Pa, in.mat[1].sigma_Hlim_Pa);
  const double Z_L = lubricant_factor(s_Hlim, in.nu40_mm2_s);
  const double Z_v = velocity_factor(s_Hlim, m.v_m_s);
  const double Z_R = roughness_factor(s_Hlim, in.flank_Rz_um[0], in.flank_Rz_um[1], g.rho_red);
  const std::array<double, 2> Z_W =
      work_hardening_factors(g, in.mat, in.flank_Rz_um, in.nu40_mm2_s, m.v_m_s);
  constexpr double kZ_X = 1.0;  // ISO 6336-2:2006, clause 14: 1 for the sizes it covers
  const double sigma_H0 = nominal_contact_stress(g, in.F_t_N, Z_H, Z_E, m.Z_eps, Z_beta);
  const double K = in.K_A * m.dyn.K_v * m.face.K_Hbeta * m.trans.K_Halpha;
  ModeResult r;
  for (int k = 0; k < 2; ++k) {
    r.sigma[k] = Z_BD[k] * sigma_H0 * std::sqrt(K);
    r.sigma_static_load[k] = r.sigma[k] * std::sqrt(static_ratio(in, m));
    r.line[k] = pitting_life_line(in.mat[k], in.limited_pitting);
    // Static: Z_L Z_v Z_R = 1 and Z_X = 1; the reference: all of them.
    r.G_static[k] = in.mat[k].sigma_Hlim_Pa * static_factor(r.line[k]) * Z_W[k];
    r.G_ref[k] = in.mat[k].sigma_Hlim_Pa * Z_L * Z_v * Z_R * Z_W[k] * kZ_X;
    finish_mode(in, r, in.optimum_long_life, k);
  }
  factors.update({{"Z_H", Z_H},
                  {"Z_E_sqrt_MPa", Z_E / 1e3},
                  {"Z_eps", m.Z_eps},
                  {"Z_beta", Z_beta},
                  {"Z_B", Z_BD[0]},
                  {"Z_D", Z_BD[1]},
                  {"Z_L", Z_L},
                  {"Z_v", Z_v},
                  {"Z_R", Z_R},
                  {"Z_W", Z_W},
                  {"Z_X", kZ_X},
                  {"Z_NT", r.life_factor}});
  out = {{"sigma_H0_Pa", sigma_H0},
         {"sigma_H_Pa", r.sigma},
         {"sigma_Hlim_Pa", {in.mat[0].sigma_Hlim_Pa, in.mat[1].sigma_Hlim_Pa}},
         {"sigma_HG_Pa", r.G},
         {"sigma_HP_Pa", {r.G[0] / in.required_S_H, r.G[1] / in.required_S_H}},
         {"S_H", r.S},
         {"required_S_H", in.required_S_H}};
  return r;
}

ModeResult bending(const RatingInput& in, const Mesh& m, json& factors, json& out) {
  const PairGeometry& g = m.g;
  const PairSpec& s = g.spec;
  const double Y_beta = helix_factor(g);
  const double Y_DT = deep_tooth_factor(g.eps_alpha_n, in.accuracy_grade);
  const double K = in.K_A * m.dyn.K_v * m.face.K_Fbeta * m.trans.K_Falpha;
  ModeResult r;
  json per = {
      {"Y_F", json::array()},         {"Y_S", json::array()},      {"Y_B", json::array()},
      {"Y_deltarelT", json::array()}, {"Y_RrelT", json::array()},  {"Y_X", json::array()},
      {"s_Fn_mm", json::array()},     {"rho_F_mm", json::array()}, {"h_Fe_mm", json::array()}};
  json sigma_F0 = json::array();
  for (int k = 0; k < 2; ++k) {
    ToothFormInput t{s.m_n, s.alpha_n, g.z_n[k], s.x[k], s.tool, 0.0};
    t.d_en = outer_single_contact_diameter(g, k);
    const IsoToothForm f = virtual_tooth_form(t);
    const double Y_B = rim_factor(in.rim_m[k], g.h[k]);
    if (std::isnan(Y_B)) {
      throw InvalidRating("/gears/" + std::to_string(k) + "/rim_thickness_mm",
                          "is below half the tooth depth, where ISO 6336-3's rim factor ends "
                          "(a rim that thin may crack through the rim)");
    }
    const double s0 = in.F_t_N / (s.b * s.m_n) * f.Y_F * f.Y_S * Y_beta * Y_B * Y_DT;
    const double Y_d = notch_sensitivity_factor(in.mat[k], f.s_Fn / (2.0 * f.rho_F));
    const double Y_R = surface_factor(in.mat[k], in.root_Rz_um[k]);
    const double Y_X = size_factor(in.mat[k], s.m_n);
    r.sigma[k] = s0 * K;
    r.sigma_static_load[k] = r.sigma[k] * static_ratio(in, m);
    r.line[k] = bending_life_line(in.mat[k]);
    // Static: Y_deltarelT, Y_RrelT and Y_X taken as 1 (docs/rating.md).
    r.G_static[k] = in.mat[k].sigma_Flim_Pa * kY_ST * static_factor(r.line[k]);
    r.G_ref[k] = in.mat[k].sigma_Flim_Pa * kY_ST * Y_d * Y_R * Y_X;
    finish_mode(in, r, in.optimum_long_life, k);
    sigma_F0.push_back(s0);
    for (auto [key, v] : {std::pair{"Y_F", f.Y_F},
                          {"Y_S", f.Y_S},
                          {"Y_B", Y_B},
                          {"Y_deltarelT", Y_d},
                          {"Y_RrelT", Y_R},
                          {"Y_X", Y_X},
                          {"s_Fn_mm", f.s_Fn * 1e3},
                          {"rho_F_mm", f.rho_F * 1e3},
                          {"h_Fe_mm", f.h_Fe * 1e3}}) {
      per[key].push_back(v);
    }
  }
  factors.update(per);
  factors.update({{"Y_beta", Y_beta}, {"Y_DT", Y_DT}, {"Y_ST", kY_ST}, {"Y_NT", r.life_factor}});
  out = {{"sigma_F0_Pa", sigma_F0},
         {"sigma_F_Pa", r.sigma},
         {"sigma_Flim_Pa", {in.mat[0].sigma_Flim_Pa, in.mat[1].sigma_Flim_Pa}},
         {"sigma_FG_Pa", r.G},
         {"sigma_FP_Pa", {r.G[0] / in.required_S_F, r.G[1] / in.required_S_F}},
         {"S_F", r.S},
         {"required_S_F", in.required_S_F}};
  return r;
}

json load_factors(const RatingInput& in, const Mesh& m) {
  return {{"K_A", in.K_A},
          {"K_v", m.dyn.K_v},
          {"K_v_range", m.dyn.range},
          {"resonance_ratio_N", m.dyn.N},
          {"n_E1_rpm", m.dyn.n_E1_rpm},
          {"K_Hbeta", m.face.K_Hbeta},
          {"K_Hbeta_from", m.face.K_Hbeta_from},
          {"K_Fbeta", m.face.K_Fbeta},
          {"N_F", m.face.N_F},
          {"K_Halpha", m.trans.K_Halpha},
          {"K_Falpha", m.trans.K_Falpha},
          {"c_prime_N_mm_um", m.c.c_prime},
          {"c_th_N_mm_um", m.c.c_th},
          {"c_gamma_alpha_N_mm_um", m.c.c_gamma_alpha},
          {"c_gamma_beta_N_mm_um", m.c.c_gamma_beta},
          {"y_alpha_um", m.dyn.y_alpha_um},
          {"F_betax_um", m.face.F_betax_um},
          {"F_betay_um", m.face.F_betay_um}};
}

json geometry_json(const RatingInput& in, const Mesh& m) {
  const PairGeometry& g = m.g;
  auto mm = [](const std::array<double, 2>& a) { return json{a[0] * 1e3, a[1] * 1e3}; };
  return {{"type", in.pair.rack ? "rack" : "external"},
          {"d_mm", mm(g.d)},
          {"d_b_mm", mm(g.d_b)},
          {"d_a_mm", mm(g.d_a)},
          {"d_f_mm", mm(g.d_f)},
          {"z_n", g.z_n},
          {"a_w_mm", in.pair.rack ? json(nullptr) : json(g.a_w * 1e3)},
          {"alpha_t_deg", g.alpha_t * 180.0 / kPi},
          {"alpha_wt_deg", g.alpha_wt * 180.0 / kPi},
          {"beta_b_deg", g.beta_b * 180.0 / kPi},
          {"eps_alpha", g.eps_alpha},
          {"eps_beta", g.eps_beta},
          {"eps_gamma", g.eps_gamma},
          {"u", in.pair.rack ? json(nullptr) : json(g.u)},
          {"d_en_mm",
           {outer_single_contact_diameter(g, 0) * 1e3, outer_single_contact_diameter(g, 1) * 1e3}}};
}

// Cycles and hours at which each gear's safety falls to the required one;
// null past 1e10 cycles (or on the optimum line: never).
json life_at_required(const RatingInput& in, const ModeResult& r, double required) {
  json cycles = json::array(), hours = json::array();
  for (int k = 0; k < 2; ++k) {
    const double n = cycles_to_stress(r.line[k], r.G_static[k], r.G_ref[k], required * r.sigma[k],
                                      in.optimum_long_life);
    const bool endless = !std::isfinite(n);
    cycles.push_back(endless ? json(nullptr) : json(n));
    hours.push_back(endless ? json(nullptr) : json(n / in.cycles[k] * in.life_h));
  }
  return {{"cycles", cycles}, {"hours", hours}, {"required_S", required}};
}

json static_check(const RatingInput& in, const ModeResult& H, const ModeResult& F) {
  json yield = json::array();
  for (int k = 0; k < 2; ++k) {
    const double y = in.mat[k].yield_Pa;
    yield.push_back(y > 0.0 ? json(y / F.sigma_static_load[k]) : json(nullptr));
  }
  return {{"tangential_force_N", in.F_static_N},
          {"sigma_H_Pa", H.sigma_static_load},
          {"sigma_F_Pa", F.sigma_static_load},
          {"S_H", H.S_static},
          {"S_F", F.S_static},
          {"Z_NT", {static_factor(H.line[0]), static_factor(H.line[1])}},
          {"Y_NT", {static_factor(F.line[0]), static_factor(F.line[1])}},
          {"S_yield", yield}};
}

// The failure mode with the smallest safety over its required value.
json governing(const RatingInput& in, const ModeResult& H, const ModeResult& F) {
  const char* gear[2] = {"pinion", in.pair.rack ? "rack" : "wheel"};
  json modes = json::array();
  for (int k = 0; k < 2; ++k) {
    modes.push_back({{"mode", std::string("pitting of the ") + gear[k]},
                     {"S", H.S[k]},
                     {"required", in.required_S_H}});
    modes.push_back({{"mode", std::string("root bending of the ") + gear[k]},
                     {"S", F.S[k]},
                     {"required", in.required_S_F}});
    modes.push_back({{"mode", std::string("static pitting of the ") + gear[k]},
                     {"S", H.S_static[k]},
                     {"required", in.required_S_H}});
    modes.push_back({{"mode", std::string("static root bending of the ") + gear[k]},
                     {"S", F.S_static[k]},
                     {"required", in.required_S_F}});
  }
  for (json& mode : modes)
    mode["margin"] = mode["S"].get<double>() / mode["required"].get<double>();
  std::stable_sort(modes.begin(), modes.end(), [](const json& a, const json& b) {
    return a["margin"].get<double>() < b["margin"].get<double>();
  });
  return {{"mode", modes[0]["mode"]},
          {"margin", modes[0]["margin"]},
          {"holds", modes[0]["margin"].get<double>() >= 1.0},
          {"modes", modes}};
}

}  // namespace

nlohmann::json rate(const RatingInput& in) {
  const Mesh m = mesh_of(in);
  json factors = load_factors(in, m), pit, bend;
  const ModeResult H = pitting(in, m, factors, pit);
  const ModeResult F = bending(in, m, factors, bend);
  json materials = json::array();
  for (const GearMaterial& g : in.mat) {
    materials.push_back({{"class", g.class_label},
                         {"quality", g.quality},
                         {"sigma_Hlim_Pa", g.sigma_Hlim_Pa},
                         {"sigma_Flim_Pa", g.sigma_Flim_Pa},
                         {"limits_from", g.limits_from}});
  }
  return {{"name", in.name},
          {"method", "ISO 6336-1, -2, -3:2006 method B; limits ISO 6336-5:2016"},
          {"geometry", geometry_json(in, m)},
          {"load",
           {{"F_t_N", in.F_t_N},
            {"v_m_s", m.v_m_s},
            {"line_load_N_mm", m.line_load_N_mm},
            {"cycles", in.cycles},
            {"life_h", in.life_h}}},
          {"materials", materials},
          {"pitting", pit},
          {"bending", bend},
          {"static", static_check(in, H, F)},
          {"factors", factors},
          {"life",
           {{"pitting", life_at_required(in, H, in.required_S_H)},
            {"bending", life_at_required(in, F, in.required_S_F)}}},
          {"governing", governing(in, H, F)}};
}

}  // namespace gearsph::gear::iso6336
