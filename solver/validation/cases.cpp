#include "solver/validation/cases.hpp"

#include <cmath>
#include <cstdio>
#include <utility>

#include "solver/gear/iso6336_rating.hpp"

namespace gearsph {
// schemas/examples/rating-iso-tr-6336-30-1.json (generated: rating_example_text.cpp.in).
extern const char* const kRatingExample1Text;
}  // namespace gearsph

namespace gearsph::validation {

namespace {

using nlohmann::json;

const char* const kKernels[] = {"seed_quartic", "cubic_spline", "quintic_spline", "wendland_c2"};

// An analysis field by its path below "analysis" (e.g. "static_check/lewis_Pa").
const json* field(const json& summary, const std::string& path) {
  if (!summary.contains("analysis")) return nullptr;
  const json::json_pointer ptr("/" + path);
  const json& a = summary.at("analysis");
  return a.contains(ptr) && !a.at(ptr).is_null() ? &a.at(ptr) : nullptr;
}

std::string missing(const json& summary) {
  return "no measurement (" + summary.value("message", std::string("see summary")) + ")";
}

// |measured - reference| / reference from two analysis fields.
std::function<Measurement(const json&, double)> relative(const std::string& measured,
                                                         const std::string& reference) {
  return [=](const json& summary, double tol) {
    Measurement m;
    const json* got = field(summary, measured);
    const json* ref = field(summary, reference);
    if (!got || !ref) {
      m.note = missing(summary);
      return m;
    }
    m.measured = got->get<double>();
    m.reference = ref->get<double>();
    m.error = (m.measured - m.reference) / m.reference;
    m.pass = std::abs(m.error) <= tol && summary.at("status") == "completed";
    return m;
  };
}

// measured / scale (scale 1 when not given) must stay below the tolerance.
std::function<Measurement(const json&, double)> bounded(const std::string& measured,
                                                        const std::string& scale) {
  return [=](const json& summary, double tol) {
    Measurement m;
    const json* got = field(summary, measured);
    const json* ref = scale.empty() ? nullptr : field(summary, scale);
    if (!got || (!scale.empty() && !ref)) {
      m.note = missing(summary);
      return m;
    }
    m.measured = got->get<double>();
    m.reference = ref ? ref->get<double>() : 1.0;
    m.error = m.measured / m.reference;
    m.pass = m.error <= tol && summary.at("status") == "completed";
    return m;
  };
}

// A yes/no outcome (1 or 0) that must equal the expected one.
std::function<Measurement(const json&, double)> outcome(const std::string& flag, bool expected) {
  return [=](const json& summary, double) {
    Measurement m;
    const json* got = field(summary, flag);
    if (!got) {
      m.note = missing(summary);
      return m;
    }
    m.measured = got->get<bool>() ? 1.0 : 0.0;
    m.reference = expected ? 1.0 : 0.0;
    m.error = m.measured - m.reference;
    m.pass = m.error == 0.0 && summary.at("status") == "completed";
    return m;
  };
}

// A text outcome (analysis.crack.outcome) that must equal the expected one:
// measured 1 when it does.
std::function<Measurement(const json&, double)> text_outcome(const std::string& path,
                                                             const std::string& expected) {
  return [=](const json& summary, double) {
    Measurement m;
    const json* got = field(summary, path);
    if (!got || !got->is_string()) {
      m.note = missing(summary);
      return m;
    }
    m.measured = got->get<std::string>() == expected ? 1.0 : 0.0;
    m.reference = 1.0;
    m.error = m.measured - m.reference;
    m.pass = m.error == 0.0 && summary.at("status") == "completed";
    m.note = got->get<std::string>() + " (expected " + expected + ")";
    return m;
  };
}

// |measured - published| / published: an analysis field against a value a
// publication gives (not one the run computes beside it).
std::function<Measurement(const json&, double)> published(const std::string& measured,
                                                          double reference) {
  return [=](const json& summary, double tol) {
    Measurement m;
    const json* got = field(summary, measured);
    if (!got) {
      m.note = missing(summary);
      return m;
    }
    m.measured = got->get<double>();
    m.reference = reference;
    m.error = (m.measured - m.reference) / m.reference;
    m.pass = std::abs(m.error) <= tol && summary.at("status") == "completed";
    return m;
  };
}

// ISO/TR 6336-30:2017, Example 1, rated from the shipped document against
// its published results (as tabulated beside gfsReboucas/Drivetrain's
// MATISO_6336.m; the references of tests/test_rating.cpp), each within the
// issue's 0.5 %. Quick and full alike: the rating is arithmetic.
void add_rating_cases(std::vector<Case>& out) {
  const json document = json::parse(kRatingExample1Text);
  struct Claim {
    const char* name;
    const char* quantity;
    const char* path;  // below analysis/rating
    double reference;
  };
  const Claim claims[] = {
      {"sigma_H_pinion", "contact stress sigma_H of the pinion [Pa]", "pitting/sigma_H_Pa/0",
       1301.4e6},
      {"sigma_H_wheel", "contact stress sigma_H of the wheel [Pa]", "pitting/sigma_H_Pa/1",
       1301.4e6},
      {"S_H_pinion", "pitting safety S_H of the pinion", "pitting/S_H/0", 1.0285},
      {"S_H_wheel", "pitting safety S_H of the wheel", "pitting/S_H/1", 1.0870},
      {"Z_NT_pinion", "life factor Z_NT of the pinion", "factors/Z_NT/0", 0.910},
      {"Z_NT_wheel", "life factor Z_NT of the wheel", "factors/Z_NT/1", 0.962},
      {"K_v", "dynamic factor K_v (method B)", "factors/K_v", 1.003},
      {"K_Hbeta", "face load factor K_Hbeta", "factors/K_Hbeta", 1.160},
  };
  for (const Claim& c : claims) {
    Case k{std::string("rating/iso_tr_6336_30_example_1/") + c.name,
           "rating",
           c.quantity,
           "ISO/TR 6336-30:2017, Example 1 (published)",
           0.005,
           document,
           published(std::string("rating/") + c.path, c.reference)};
    k.input = Case::Input::Rating;
    out.push_back(std::move(k));
  }
}

// Lewicki & Ballarini's test gear (NASA TM-107229; J. Mech. Des. 119, 1997):
// 28 teeth, module 3.175 mm (diametral pitch 8), 20 degrees, face 6.35 mm,
// loaded at the highest point of single tooth contact, with a rim of backup
// ratio m_B; the crack starts at the fillet's tension peak, normal to it,
// about as short as the ring that reads K allows (8 spacings: 1.30 mm).
json lewicki_crack_job(double backup_ratio) {
  return {{"name", "lewicki-ballarini-mB-" + std::to_string(backup_ratio)},
          {"scene",
           {{"type", "rack_pinion"},
            {"quasi_static", true},
            {"contact_point", "hpstc"},
            {"pinion",
             {{"omega_rad_s", 0.0},
              {"teeth", 28},
              {"module_mm", 3.175},
              {"face_width_mm", 6.35},
              {"backup_ratio", backup_ratio}}},
            {"rack", {{"velocity_m_s", 0.0}, {"load_N", 2000.0}}},
            {"crack", {{"fillet_position", "peak"}, {"length_mm", 1.4}, {"angle_deg", 0.0}}}}},
          {"output", {{"frames", 0}}}};
}

json plate_job(const std::string& kernel) {
  return {{"name", "plate-" + kernel},
          {"scene", {{"type", "plate"}, {"length_m", 0.2}, {"thickness_m", 0.02}, {"Vf", 0.01}}},
          {"discretization", {{"spacing_m", 0.002}, {"kernel", kernel}}}};
}

json strip_job(const std::string& kernel, const std::string& lateral, bool quick) {
  // Steel strip; the pulse is 4 % of the length, long against the thickness.
  const double length = quick ? 0.3 : 0.6;
  return {{"name", "strip-" + lateral + "-" + kernel},
          {"scene",
           {{"type", "strip_wave"},
            {"length_m", length},
            {"thickness_m", lateral == "free" ? 0.006 : 0.004},
            {"lateral", lateral}}},
          {"discretization", {{"spacing_m", quick ? 0.001 : 0.0005}, {"kernel", kernel}}}};
}

json disk_job(const std::string& kernel, bool driven, bool quick) {
  json scene = {
      {"type", "spinning_disk"}, {"radius_m", 0.02}, {"omega_rad_s", 2000.0}, {"driven", driven}};
  json job = {{"name", std::string("disk-") + (driven ? "driven-" : "free-") + kernel},
              {"scene", scene},
              {"discretization", {{"spacing_m", quick ? 0.002 : 0.001}, {"kernel", kernel}}}};
  if (driven) {
    // The rotated-stress check is about the Jaumann rate, i.e. the
    // updated-Lagrangian stress update (total Lagrangian has no stress rate).
    scene["initial_stress_Pa"] = {{"xx", 50e6}, {"yy", -20e6}, {"xy", 10e6}};
    job["scene"] = scene;
    job["method"] = {{"formulation", "updated_lagrangian"}};
  }
  return job;
}

// Two steel bars, 1 m/s each; the kernel variant couples them through the
// SPH sums (updated Lagrangian), the coupling the seed paper's force replaces.
json bar_job(bool kernel_coupling, bool quick) {
  json job = {{"name", kernel_coupling ? "bar-impact-kernel" : "bar-impact"},
              {"scene", {{"type", "bar_impact"}, {"length_m", quick ? 0.05 : 0.1}}},
              {"discretization", {{"spacing_m", quick ? 0.001 : 0.0005}}}};
  if (kernel_coupling) {
    job["method"] = {{"formulation", "updated_lagrangian"}, {"contact", {{"model", "kernel"}}}};
  }
  return job;
}

// A lattice job's graded twin: body-fitted particles, a quarter of the bulk
// spacing at the scene's stress raiser (graded 4:1 in each body, at the
// default rate), so the suite's references check the graded operator too.
json graded(json job) {
  job["name"] = job.at("name").get<std::string>() + "-graded";
  const double dx = job.at("discretization").at("spacing_m").get<double>();
  job["discretization"]["particles"] = "body_fitted";
  job["discretization"]["fine_spacing_m"] = 0.25 * dx;
  return job;
}

// Steel cylinder on a steel block, 2 MN/m: a = 0.48 mm, p0 = 2.6 GPa, six
// spacings across a (docs/contact.md). The quick variant has a smaller block.
json hertz_job(bool quick) {
  const double box = quick ? 6.0 : 12.0;  // smaller blocks do not relax within the run
  return {{"name", "hertz"},
          {"scene",
           {{"type", "hertz"},
            {"cap_height_over_a", box},
            {"block_half_width_over_a", box},
            {"block_depth_over_a", box}}},
          {"discretization", {{"spacing_m", 8e-5}}}};  // a / 6: a / 4 is 13 % off
}

// The same contact on body-fitted particles graded 4:1, a/12 at the contact
// and a/3 far from it: a third of the lattice's particles at half its
// spacing where it matters (docs/contact.md, "Resolved contact").
json hertz_graded_job(bool quick) {
  json job = hertz_job(quick);
  job["name"] = "hertz-graded";
  job["discretization"] = {
      {"particles", "body_fitted"}, {"fine_spacing_m", 4e-5}, {"spacing_m", 1.6e-4}};
  return job;
}

// The seed paper's pair held at its starting position (no rotation, no rack
// speed) while a 1 kN rack force is ramped on and the motion relaxed: the
// static tooth load of validation.md section 7.
json gear_static_job() {
  return {{"name", "gear-static"},
          {"scene",
           {{"type", "rack_pinion"},
            {"quasi_static", true},
            {"pinion", {{"omega_rad_s", 0.0}}},
            {"rack", {{"velocity_m_s", 0.0}, {"load_N", 1000.0}}}}}};
}

// A static check of the seed paper's pinion with tooth 0 loaded alone at
// `contact_point` (1 kN rack load), at the default particles.
json gear_fillet_job(const std::string& contact_point) {
  return {{"name", "gear-fillet-" + contact_point},
          {"scene",
           {{"type", "rack_pinion"},
            {"quasi_static", true},
            {"contact_point", contact_point},
            {"pinion", {{"omega_rad_s", 0.0}}},
            {"rack", {{"velocity_m_s", 0.0}, {"load_N", 1000.0}}}}}};
}

// A static check whose contact the particles resolve (scene
// resolve_contact: a spacing of a fraction of the Hertz half-width at tooth
// 0's contact, pitch point). Quick: 20 kN, where a is 4.5 times the 1 kN
// one's and the run takes a fifth of the steps; the ratio of spacing to
// half-width, which sets the error, is the same.
json gear_resolved_contact_job(bool quick) {
  return {{"name", "gear-resolved-contact"},
          {"scene",
           {{"type", "rack_pinion"},
            {"quasi_static", true},
            {"resolve_contact", true},
            {"pinion", {{"omega_rad_s", 0.0}}},
            {"rack", {{"velocity_m_s", 0.0}, {"load_N", quick ? 20000.0 : 1000.0}}}}},
          {"output", {{"frames", 0}}}};
}

// Kirsch: d/W = 0.2, L = 3 W (quick: a smaller plate, L = 2 W), the default
// body-fitted particles (a/10 at the hole).
json kirsch_job(bool quick) {
  return {{"name", "kirsch"},
          {"scene",
           {{"type", "plate_with_hole"},
            {"width_m", quick ? 0.02 : 0.04},
            {"length_m", quick ? 0.04 : 0.12},
            {"hole_radius_m", quick ? 0.002 : 0.004}}}};
}

// A cracked plate (docs/cracks.md), W = 40 mm, L = 2 W, spacing a / n.
json cracked_plate_job(const std::string& kind, double length, double angle_deg, double n) {
  const double a = kind == "edge" ? length : 0.5 * length;
  return {{"name", "cracked-plate-" + kind},
          {"scene",
           {{"type", "cracked_plate"},
            {"width_m", 0.04},
            {"length_m", 0.08},
            {"crack", {{"kind", kind}, {"length_m", length}, {"angle_deg", angle_deg}}}}},
          {"discretization", {{"spacing_m", a / n}}}};
}

// Kirsch off the default d/W: 0.1 (a small hole in a wide plate) and 0.5.
json kirsch_hole_job(double d_over_w) {
  const double width = 0.04;
  return {{"name", "kirsch"},
          {"scene",
           {{"type", "plate_with_hole"},
            {"width_m", width},
            {"length_m", 3.0 * width},
            {"hole_radius_m", 0.5 * d_over_w * width}}}};
}

// Lame off the default b/a = 2: a thin ring (1.5) and a thick one (4), the
// ends of what the bore reading is claimed for (steel, 50 MPa).
json lame_ring_job(double b_over_a) {
  const double a = 0.02;
  return {{"name", "lame"},
          {"scene",
           {{"type", "thick_cylinder"},
            {"inner_radius_m", a},
            {"outer_radius_m", b_over_a * a},
            {"pressure_Pa", 5e7},
            {"material", {{"E_Pa", 2.1e11}, {"nu", 0.3}, {"rho_kg_m3", 7850}}}}},
          {"output", {{"frames", 0}}}};
}

json lame_job() {
  return {{"name", "lame"}, {"scene", {{"type", "thick_cylinder"}}}};
}

// Waves, vibration and rigid rotation: the elastic terms on their own.
void add_elastic_wave_cases(std::vector<Case>& out, bool quick) {
  for (const char* k : kKernels) {
    out.push_back({std::string("plate_period/") + k, "5", "period [s]",
                   "thin plate, omega^2 = E H^2 k^4 / (12 rho (1 - nu^2))", 0.05, plate_job(k),
                   relative("period_s", "reference_period_s")});
  }
  for (const char* lateral : {"confined", "free"}) {
    for (const char* k : kKernels) {
      const std::string lat = lateral;
      out.push_back(
          {"wave_speed_" + lat + "/" + k, "2", "wave speed [m/s]",
           lat == "confined" ? "c_p = sqrt((K + 4G/3)/rho)" : "c = sqrt(E / (rho (1 - nu^2)))",
           0.02, strip_job(k, lat, quick), relative("wave_speed_m_s", "reference_speed_m_s")});
    }
  }
  for (const char* k : kKernels) {
    // A free spinning disk: the von Mises stress stays at the centrifugal
    // level (steady 0.17, dynamic peak <= ~0.35 rho omega^2 R^2), far below
    // what any spurious strain rate would build (G omega t).
    out.push_back({std::string("disk_free/") + k, "4", "max von Mises / (rho omega^2 R^2)",
                   "centrifugal stress scale; steady centre value 0.171", 0.5,
                   disk_job(k, false, quick), bounded("max_von_mises_Pa", "centrifugal_scale_Pa"),
                   Case::Kind::Bound});
    out.push_back({std::string("disk_rotated_stress/") + k, "4",
                   "max |S - R S0 R^T| / |S0| over one revolution", "S(t) = R(wt) S0 R(wt)^T", 0.01,
                   disk_job(k, true, quick), bounded("max_stress_rotation_error", ""),
                   Case::Kind::Bound});
  }
  // Graded twins of the lattice cases (the default kernel): the same
  // references through body-fitted particles graded 4:1 (docs/validation.md).
  out.push_back({"plate_period_graded/seed_quartic", "5", "period [s]",
                 "thin plate; particles 4x finer at the clamp", 0.05,
                 graded(plate_job("seed_quartic")), relative("period_s", "reference_period_s")});
  out.push_back({"wave_speed_free_graded/seed_quartic", "2", "wave speed [m/s]",
                 "c = sqrt(E / (rho (1 - nu^2))); particles 4x finer between the probes", 0.02,
                 graded(strip_job("seed_quartic", "free", quick)),
                 relative("wave_speed_m_s", "reference_speed_m_s")});
  out.push_back({"disk_free_graded/seed_quartic", "4", "max von Mises / (rho omega^2 R^2)",
                 "centrifugal stress scale; particles 4x finer at the centre", 0.5,
                 graded(disk_job("seed_quartic", false, quick)),
                 bounded("max_von_mises_Pa", "centrifugal_scale_Pa"), Case::Kind::Bound});
}

// Contact between bodies: impact of bars and Hertz's cylinder on a half-plane.
void add_contact_cases(std::vector<Case>& out, bool quick) {
  out.push_back({"bar_impact/contact_stress", "3", "contact stress [Pa]", "sigma = rho c v", 0.05,
                 bar_job(false, quick),
                 relative("contact_stress_Pa", "reference_contact_stress_Pa")});
  out.push_back({"bar_impact/contact_time", "3", "contact time [s]", "t_c = 2 L / c", 0.05,
                 bar_job(false, quick), relative("contact_time_s", "reference_contact_time_s")});
  out.push_back({"bar_impact/separates", "3", "bars separate after contact (1 yes)",
                 "elastic impact: the bars part at t_c", 0.0, bar_job(false, quick),
                 outcome("separated", true), Case::Kind::Outcome});
  out.push_back({"bar_impact_graded/contact_stress", "3", "contact stress [Pa]",
                 "sigma = rho c v; particles 4x finer at the facing ends", 0.05,
                 graded(bar_job(false, quick)),
                 relative("contact_stress_Pa", "reference_contact_stress_Pa")});
  out.push_back({"bar_impact_graded/contact_time", "3", "contact time [s]",
                 "t_c = 2 L / c; particles 4x finer at the facing ends", 0.05,
                 graded(bar_job(false, quick)),
                 relative("contact_time_s", "reference_contact_time_s")});
  out.push_back({"bar_impact_kernel/sticks", "3", "bars separate after contact (1 yes)",
                 "kernel coupling holds the bars together (adhesion)", 0.0, bar_job(true, quick),
                 outcome("separated", false), Case::Kind::Outcome});
  // Hertz's half-plane needs the full variant's block (12a): there the
  // lattice at a/6 is within 5 % (-2.1 %, -1.1 %); the quick variant's 6a
  // block costs about 6 points (docs/contact.md).
  const double hertz_tolerance = quick ? 0.10 : 0.05;
  out.push_back({"hertz/peak_pressure", "6", "peak pressure p0 [Pa]", "p0 = 2 P' / (pi a)",
                 hertz_tolerance, hertz_job(quick),
                 relative("peak_pressure_Pa", "reference_peak_pressure_Pa")});
  out.push_back({"hertz/half_width", "6", "contact half-width a [m]", "a = sqrt(4 P' R / (pi E*))",
                 hertz_tolerance, hertz_job(quick),
                 relative("half_width_m", "reference_half_width_m")});
  out.push_back({"hertz_graded/peak_pressure", "6", "peak pressure p0 [Pa]", "p0 = 2 P' / (pi a)",
                 0.10, hertz_graded_job(quick),
                 relative("peak_pressure_Pa", "reference_peak_pressure_Pa")});
  out.push_back({"hertz_graded/half_width", "6", "contact half-width a [m]",
                 "a = sqrt(4 P' R / (pi E*))", 0.10, hertz_graded_job(quick),
                 relative("half_width_m", "reference_half_width_m")});
}

// Stress at curved free boundaries: Kirsch's hole and Lame's ring.
void add_stress_concentration_cases(std::vector<Case>& out, bool quick) {
  // Stress at a curved free boundary, recovered on the true outline
  // (validation.md section 10).
  out.push_back({"kirsch/peak_hoop_stress", "10", "peak hoop stress at the hole [Pa]",
                 "Howland's finite-width plate (Heywood: Kt_net = 2 + (1 - d/W)^3)", 0.03,
                 kirsch_job(quick),
                 relative("peak_hoop_stress_Pa", "reference_peak_hoop_stress_Pa")});
  out.push_back({"lame/bore_hoop_stress", "10", "hoop stress at the bore [Pa]",
                 "Lame: p (b^2 + a^2) / (b^2 - a^2)", 0.02, lame_job(),
                 relative("bore_hoop_stress_Pa", "reference_bore_hoop_stress_Pa")});
  for (const double d_over_w : {0.1, 0.5}) {
    if (quick && d_over_w < 0.2) continue;  // 30 s: the full variant's
    out.push_back(
        {std::string("kirsch/peak_hoop_stress_d_over_w_") + (d_over_w < 0.2 ? "0.1" : "0.5"), "10",
         "peak hoop stress at the hole [Pa]",
         "Howland's finite-width plate (Heywood: Kt_net = 2 + (1 - d/W)^3)", 0.03,
         kirsch_hole_job(d_over_w),
         relative("peak_hoop_stress_Pa", "reference_peak_hoop_stress_Pa")});
  }
  for (const double b_over_a : {1.5, 4.0}) {
    out.push_back({std::string("lame/bore_hoop_stress_b_over_a_") + (b_over_a < 2 ? "1.5" : "4"),
                   "10", "hoop stress at the bore [Pa]", "Lame: p (b^2 + a^2) / (b^2 - a^2)", 0.02,
                   lame_ring_job(b_over_a),
                   relative("bore_hoop_stress_Pa", "reference_bore_hoop_stress_Pa")});
  }
  out.push_back({"lame/bore_displacement", "10", "radial displacement of the bore [m]",
                 "Lame, plane strain: (1 + nu) p a^2 / (E (b^2 - a^2)) [(1 - 2 nu) a + b^2 / a]",
                 0.02, lame_job(),
                 relative("bore_displacement_m", "reference_bore_displacement_m")});
}

// Cracks: stress intensity factors in a plate and the outcome of a root crack in a gear.
void add_crack_cases(std::vector<Case>& out, bool quick) {
  // Stress intensity factors of a crack cut in the particles, by the
  // interaction integral (docs/cracks.md), at the tolerances (K_I
  // 3 %, K_II 5 %). The error falls at first order with the spacing (the
  // cut crack reads about half a spacing long): the edge crack takes a/20
  // in the quick variant (+2.7 %), a/40 in the full one (+1.2 %); the 30
  // degree centre crack's K_I is +4.5 % at a/10 and +3.2 % at a/20, so it is
  // reported, not claimed, until the tip is refined; its K_II (+2.3 % at
  // a/10, -0.1 % at a/20) is claimed.
  out.push_back({"cracked_plate/edge_K_I", "cracks", "K_I of an edge crack, a/W = 0.3 [Pa m^0.5]",
                 "Tada: sigma sqrt(pi a) F(a/W), F = 1.12 - 0.231 s + 10.55 s^2 - ...", 0.03,
                 cracked_plate_job("edge", 0.012, 0.0, quick ? 20.0 : 40.0),
                 relative("K_I_Pa_sqrt_m", "reference_K_I_Pa_sqrt_m")});
  const json centre = cracked_plate_job("centre", 0.012, 30.0, quick ? 10.0 : 20.0);
  out.push_back({"cracked_plate/centre_30deg_K_I", "cracks",
                 "K_I of a centre crack at 30 deg, 2a/W = 0.3 [Pa m^0.5]",
                 "Tada: sigma cos^2(b) sqrt(pi a) F(2a cos(b) / W)", 0.03, centre,
                 relative("K_I_Pa_sqrt_m", "reference_K_I_Pa_sqrt_m"), Case::Kind::Relative,
                 "+4.5 % at a/10 and +3.2 % at a/20, falling at first order (docs/cracks.md): "
                 "the 3 % needs a finer tip"});
  out.push_back({"cracked_plate/centre_30deg_K_II", "cracks",
                 "K_II of a centre crack at 30 deg, 2a/W = 0.3 [Pa m^0.5]",
                 "Tada: sigma sin(b) cos(b) sqrt(pi a) F(2a cos(b) / W)", 0.05, centre,
                 relative("K_II_Pa_sqrt_m", "reference_K_II_Pa_sqrt_m")});
  // Root cracks in the gear (docs/cracks.md, "The gear"): Lewicki &
  // Ballarini's clear outcomes, through the tooth at m_B 3.3 and 1.0, through
  // the rim at 0.3 (their predictions and tests agree there; at 0.5 they
  // went either way and are not a case). Quick: the two ends, 1.0 and 0.3.
  const std::vector<std::pair<double, std::string>> lewicki =
      quick ? std::vector<std::pair<double, std::string>>{{1.0, "tooth"}, {0.3, "rim"}}
            : std::vector<std::pair<double, std::string>>{
                  {3.3, "tooth"}, {1.0, "tooth"}, {0.3, "rim"}};
  for (const auto& [ratio, expected] : lewicki) {
    char id[64];
    std::snprintf(id, sizeof id, "gear_crack/lewicki_mB_%.1f", ratio);
    // The thin rim's crack runs along the rim, not through it, on a bore
    // held right under it: the rim cannot bend (docs/cracks.md).
    const std::string disagreement =
        ratio < 0.5 ? "measured tooth: the rim held at its bore cannot bend as the test gear's "
                      "did (docs/cracks.md)"
                    : "";
    out.push_back({id, "cracks", "crack outcome (1: " + expected + ")",
                   "Lewicki & Ballarini 1997 (NASA TM-107229): tests and FRANC predictions", 0.0,
                   lewicki_crack_job(ratio), text_outcome("crack/outcome", expected),
                   Case::Kind::Outcome, disagreement});
  }
}

// The gear against ISO 6336: root bending, mesh stiffness, contact pressure, the fillet.
void add_gear_cases(std::vector<Case>& out, bool quick) {
  // Nominal bending stress of tooth 0's critical section (6 M / s_Fn^2),
  // against ISO's form factor for the load where it acts.
  out.push_back(
      {"gear_static/root_bending_iso", "7", "nominal root bending stress [Pa]",
       "ISO 6336-3 Ft / (b m) Y_F, Y_F where the load acts", 0.20, gear_static_job(),
       relative("static_check/nominal_bending_stress_Pa", "static_check/iso_nominal_Pa")});
  out.push_back({"gear_static/root_bending_lewis", "7", "nominal root bending stress [Pa]",
                 "Lewis Ft / (b m Y), Y = 0.245 (z = 12), load at the tip", 0.40, gear_static_job(),
                 relative("static_check/nominal_bending_stress_Pa", "static_check/lewis_Pa"),
                 Case::Kind::Relative,
                 "Lewis's Y assumes the load at the tip; the static check loads the pitch point "
                 "(r = 24 mm), where ISO's Y_F is 0.6 of its tip value"});
  // The elastic pair the particles model is ISO's theoretical stiffness
  // c'_th: a finite-element model of the same pinion and rack tooth gives
  // 13.6 N/(mm um) at the pitch point, c'_th within 1 % (docs/fe-check.md).
  // ISO's c' is 0.8 c'_th (C_M), the measured gears' extra compliance that
  // the model has no source for; it is reported beside it.
  out.push_back({"gear_static/mesh_stiffness", "7", "single-pair mesh stiffness [N/(mm um)]",
                 "ISO 6336-1 c'_th (method B, before C_M = 0.8)", 0.15, gear_static_job(),
                 relative("static_check/mesh_stiffness_N_per_mm_um",
                          "static_check/iso_theoretical_mesh_stiffness_N_per_mm_um")});
  out.push_back(
      {"gear_static/mesh_stiffness_iso_measured", "7", "single-pair mesh stiffness [N/(mm um)]",
       "ISO 6336-1 c' = 0.8 c'_th", 0.15, gear_static_job(),
       relative("static_check/mesh_stiffness_N_per_mm_um",
                "static_check/iso_mesh_stiffness_N_per_mm_um"),
       Case::Kind::Relative,
       "c' carries ISO's C_M = 0.8 for measured solid gears (shafts, bearings, deviations), "
       "none of which the elastic pair has; the finite-element pair matches c'_th"});
  // ISO 6336-2's sigma_H0 is the Hertz pressure at the pitch point: the
  // sub-model on the resolved tooth force and the measured flank curvature
  // must give it where the load sits there.
  out.push_back(
      {"gear_static/contact_pressure_pitch", "7", "Hertz peak pressure at the pitch point [Pa]",
       "ISO 6336-2 sigma_H0 = Z_H Z_E sqrt(Ft / (d b)), one pair", 0.02, gear_fillet_job("pitch"),
       relative("static_check/hertz_peak_pressure_Pa", "static_check/iso_sigma_H0_Pa")});
  // The same pressure read from particles that resolve the contact.
  out.push_back(
      {"gear_static/resolved_contact_pressure", "7",
       "peak contact pressure read from the particles [Pa]",
       "Hertz p0 on tooth 0's force and flank curvature (the sub-model above)", 0.10,
       gear_resolved_contact_job(quick),
       relative("static_check/resolved_peak_pressure_Pa", "static_check/hertz_peak_pressure_Pa")});
  // Linear where the physics is: the fillet peak per unit load at the final
  // load against that at half of it (static_check.linearity), 7 kN.
  for (const char* point : {"hpstc", "tip"}) {
    json job = gear_fillet_job(point);
    job["scene"]["rack"]["load_N"] = 7000.0;
    job["output"] = {{"frames", 0}};
    out.push_back(
        {std::string("gear_static/fillet_linearity_") + point, "7",
         "tension fillet peak per unit tooth-0 force at 7 kN [Pa/N]",
         "the same at half the load (linear elasticity, load at a fixed point)", 0.01, job,
         relative("static_check/linearity/fillet_tension_peak_per_N_at_final_load_Pa_per_N",
                  "static_check/linearity/fillet_tension_peak_per_N_at_half_load_Pa_per_N")});
  }
  // The gear's fillet, tooth 0 loaded alone, against ISO 6336-3 method B
  // at the same load radius (its formulas' own accuracy, about 15 %).
  for (const char* point : {"pitch", "hpstc", "tip"}) {
    out.push_back(
        {std::string("gear_fillet/") + point, "10", "tension fillet peak sigma_1 [Pa]",
         "ISO 6336-3 sigma_F0 = Ft / (b m) Y_F Y_S at the load radius", 0.15,
         gear_fillet_job(point),
         relative("static_check/fillet_tension_peak_Pa", "static_check/iso_sigma_F0_Pa")});
  }
}

}  // namespace

json rating_summary(const json& document) {
  return {{"status", "completed"},
          {"analysis", {{"rating", gear::iso6336::rate_document(document)}}}};
}

std::vector<Case> cases(bool quick) {
  std::vector<Case> out;
  add_elastic_wave_cases(out, quick);
  add_contact_cases(out, quick);
  add_stress_concentration_cases(out, quick);
  add_gear_cases(out, quick);
  add_crack_cases(out, quick);
  add_rating_cases(out);
  return out;
}

}  // namespace gearsph::validation
