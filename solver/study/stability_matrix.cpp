#include "solver/study/stability_matrix.hpp"

#include <cmath>
#include <sstream>

#include "solver/run/runner.hpp"

namespace gearsph::study {

namespace {

using nlohmann::json;

// ---- methods (columns) ------------------------------------------------------

// The seed paper's method as printed: updated Lagrangian, plain kernel gradients,
// no artificial stress, no hourglass control.
json ul_paper() {
  return {{"formulation", "updated_lagrangian"},
          {"gradient_correction", "none"},
          {"artificial_stress", {{"epsilon", 0.0}}},
          {"hourglass", {{"coefficient", 0.0}}}};
}
// Monaghan's remedy for the tensile instability (Gray, Monaghan & Swift 2001).
json ul_as() {
  json m = ul_paper();
  m["artificial_stress"] = {{"epsilon", 0.3}, {"n", 4}};
  return m;
}
// UL hourglass damping; 0.5 as in the conservation tests.
constexpr double kHourglass = 0.5;
json ul_as_hg() {
  json m = ul_as();
  m["hourglass"] = {{"coefficient", kHourglass}};
  return m;
}
json ul_as_corr() {
  json m = ul_as();
  m["gradient_correction"] = "linear";  // Bonet & Lok 1999; quadratic halves the step here
  return m;
}
json ul_hg() {
  json m = ul_paper();
  m["hourglass"] = {{"coefficient", kHourglass}};
  return m;
}
json tl() {
  return {{"formulation", "total_lagrangian"}};
}
json tl_hg() {
  return {{"formulation", "total_lagrangian"}, {"hourglass", {{"coefficient", kHourglass}}}};
}
json tl_plain() {
  return {{"formulation", "total_lagrangian"}, {"gradient_correction", "none"}};
}

struct Method {
  const char* id;
  const char* label;
  json (*method)();
};

const Method kUl{"ul_paper", "UL (paper)", ul_paper};
const Method kUlAs{"ul_as", "UL + art. stress", ul_as};
const Method kUlAsHg{"ul_as_hg", "UL + AS + hourglass", ul_as_hg};
const Method kUlAsCorr{"ul_as_corr", "UL + AS + grad. corr.", ul_as_corr};
const Method kUlHg{"ul_hg", "UL + hourglass", ul_hg};
const Method kTl{"tl", "TL", tl};
const Method kTlHg{"tl_hg", "TL + hourglass", tl_hg};
const Method kTlPlain{"tl_plain", "TL, no grad. corr.", tl_plain};

json history(int points, int frames = 0) {
  return {{"history_points", points}, {"frames", frames}};
}

Cell make(const std::string& case_id, const std::string& case_label, const Method& m, json job,
          const std::string& expect, const std::string& purpose, bool quick) {
  Cell c;
  c.case_id = case_id;
  c.case_label = case_label;
  c.method_id = m.id;
  c.method_label = m.label;
  if (!job.contains("method")) job["method"] = m.method();
  job["name"] = "stability " + case_id + " / " + m.id;
  if (!job.contains("output")) job["output"] = history(400);
  c.job = std::move(job);
  c.expect = expect;
  c.documented = expect;
  c.purpose = purpose;
  c.quick = quick;
  return c;
}

// Our measurement differs from what the literature leads one to expect.
void deviates(Cell& c, const std::string& note) {
  c.documented = c.expect == "fails" ? "stable" : "fails";
  c.deviation = note;
}

// ---- cases (rows) -------------------------------------------------------------

// Strip in tension: 50 mm x 10 mm of the plate's rubber-like material,
// dx 1 mm (500 particles), pulled to 10 % strain over five transit periods
// (~700 steps).
void tension_strip(std::vector<Cell>& out) {
  const std::string id = "tension_strip", label = "strip in tension";
  auto job = [](const json& method, const std::string& kernel) {
    return json{{"scene",
                 {{"type", "tension_strip"},
                  {"length_m", 0.05},
                  {"thickness_m", 0.01},
                  {"peak_strain", 0.1}}},
                {"discretization", {{"spacing_m", 0.001}, {"kernel", kernel}}},
                {"method", method}};
  };
  const char* why = "tensile instability: particles clump where the strip is in tension";
  out.push_back(make(id, label, kUl, job(ul_paper(), "seed_quartic"), "fails", why, true));
  deviates(out.back(),
           "the paper's quartic kernel resists pairing: the closest pair reaches 0.52 dx at 10 % "
           "strain, a warning, where the other kernels pass 0.5 dx");
  out.push_back(make(id, label, kUlAs, job(ul_as(), "seed_quartic"), "stable", why, true));
  out.push_back(make(id, label, kUlAsCorr, job(ul_as_corr(), "seed_quartic"), "stable", why, true));
  out.push_back(make(id, label, kTl, job(tl(), "seed_quartic"), "stable", why, true));
  out.push_back(make(id, label, kTlHg, job(tl_hg(), "seed_quartic"), "stable", why, true));
  // Each kernel, with the seed paper's UL method and with its remedy.
  for (const char* k : {"cubic_spline", "quintic_spline", "wendland_c2"}) {
    for (const Method* m : {&kUl, &kUlAs}) {
      Cell c = make(id, label, *m, job(m->method(), k), m == &kUl ? "fails" : "stable", why, true);
      c.method_id += std::string("_") + k;
      c.method_label += std::string(", ") + k;
      c.job["name"] = "stability " + id + " / " + c.method_id;
      out.push_back(std::move(c));
    }
  }
}

// Bars colliding (validation.md 3): two 20 mm x 5 mm steel bars at +-1 m/s,
// dx 0.5 mm (800 particles), run for three contact times.
void bar_impact(std::vector<Cell>& out) {
  const std::string id = "bar_impact", label = "colliding blocks";
  auto job = [](const json& method, const char* contact) {
    json m = method;
    m["contact"] = {{"model", contact}};
    // 2 L / c = 8 us; three contact times let the bars separate and drift apart.
    return json{{"scene", {{"type", "bar_impact"}, {"length_m", 0.02}, {"thickness_m", 0.005}}},
                {"discretization", {{"spacing_m", 0.0005}}},
                {"method", m},
                {"time", {{"end_s", 2.4e-5}}}};
  };
  const char* why = "contact: bodies must bounce apart, not stick or interpenetrate";
  struct C {
    const char* contact;
    const char* mid;
    const char* mlabel;
    bool ul;
    const char* expect;
  };
  for (const C& c :
       {C{"seed_penalty", "tl_seed_penalty", "TL, contact seed_penalty", false, "stable"},
        C{"surface_penalty", "tl_surface_penalty", "TL, contact surface_penalty", false, "stable"},
        C{"hertz", "tl_hertz", "TL, contact hertz", false, "stable"},
        C{"seed_penalty", "ul_seed_penalty", "UL + AS, contact seed_penalty", true, "stable"},
        C{"kernel", "ul_kernel", "UL + AS, contact kernel", true, "fails"}}) {
    Cell cell = make(id, label, kTl, job(c.ul ? ul_as() : tl(), c.contact), c.expect, why, true);
    cell.method_id = c.mid;
    cell.method_label = c.mlabel;
    cell.job["name"] = "stability " + id + " / " + c.mid;
    cell.criterion = "stuck";
    out.push_back(std::move(cell));
  }
}

// Oscillating plate (validation.md 5), Vf = 0.05, 0.1 m x 0.01 m, dx 2 mm
// (315 particles). Quick: 3 reference periods; full: 20 periods.
void plate(std::vector<Cell>& out, bool full) {
  const std::string id = full ? "plate_20_periods" : "plate_3_periods";
  const std::string label = full ? "plate, 20 periods" : "plate, 3 periods";
  const double period = 0.127;  // thin-plate reference for these dimensions [s]
  const double periods = full ? 20.0 : 3.0;
  auto job = [&](const json& method) {
    return json{
        {"scene", {{"type", "plate"}, {"length_m", 0.1}, {"thickness_m", 0.01}, {"Vf", 0.05}}},
        {"discretization", {{"spacing_m", 0.002}}},
        {"method", method},
        {"time", {{"end_s", periods * period}}},
        {"output", history(full ? 2000 : 400)}};
  };
  const char* why = "hourglass zig-zag, amplitude decay and energy drift in bending";
  const bool q = !full;
  out.push_back(make(id, label, kUl, job(ul_paper()), "fails", why, q));
  out.push_back(make(id, label, kUlHg, job(ul_hg()), "fails", why, q));
  const char* pumping =
      "artificial stress holds the particles apart but feeds the bending: the energy balance "
      "grows steadily, past 30 % within two periods";
  out.push_back(make(id, label, kUlAs, job(ul_as()), "stable", why, q));
  deviates(out.back(), pumping);
  out.push_back(make(id, label, kUlAsHg, job(ul_as_hg()), "stable", why, q));
  deviates(out.back(), pumping);
  out.push_back(make(id, label, kUlAsCorr, job(ul_as_corr()), "stable", why, q));
  out.push_back(make(id, label, kTl, job(tl()), "stable", why, q));
  out.push_back(make(id, label, kTlHg, job(tl_hg()), "stable", why, q));
  out.push_back(make(id, label, kTlPlain, job(tl_plain()), "stable", why, q));
}

// Free spinning disk (validation.md 4) at 2000 rad/s, R = 20 mm, one
// revolution: the stress must stay at the centrifugal level.
void spinning_disk(std::vector<Cell>& out, bool full) {
  const std::string id = "spinning_disk", label = "spinning disk";
  auto job = [](const json& method, const std::string& kernel) {
    return json{{"scene", {{"type", "spinning_disk"}, {"radius_m", 0.02}, {"omega_rad_s", 2000}}},
                {"discretization", {{"spacing_m", 0.002}, {"kernel", kernel}}},
                {"method", method}};
  };
  const char* why = "objectivity: a rigid rotation must not create stress";
  auto add = [&](const Method& m, const json& method, const std::string& kernel,
                 const std::string& expect, bool quick) {
    Cell c = make(id, label, m, job(method, kernel), expect, why, quick);
    if (kernel != "seed_quartic") {
      c.method_id += "_" + kernel;
      c.method_label += ", " + kernel;
      c.job["name"] = "stability " + id + " / " + c.method_id;
    }
    c.criterion = "spurious_stress";
    out.push_back(std::move(c));
  };
  add(kUl, ul_paper(), "seed_quartic", "fails", true);
  add(kUlAs, ul_as(), "seed_quartic", "stable", true);
  deviates(out.back(),
           "without the gradient correction the plain SPH velocity gradient of a rotating "
           "lattice is not zero: spurious stress two orders above rho w^2 R^2");
  add(kUlAsCorr, ul_as_corr(), "seed_quartic", "stable", true);
  add(kTl, tl(), "seed_quartic", "stable", true);
  if (full) {
    for (const char* k : {"cubic_spline", "quintic_spline", "wendland_c2"}) {
      add(kUlAs, ul_as(), k, "fails", false);
      add(kTl, tl(), k, "stable", false);
    }
  }
}

// Time step at 1.0, 1.5 and 3 times the measured stable limit: the
// tension strip at 1 % strain with TL, so only the step can make it fail.
void time_step(std::vector<Cell>& out) {
  const std::string label = "time step x limit";
  for (double k : {1.0, 1.5, 3.0}) {
    std::ostringstream id;
    id << "dt_" << k << "x";
    json job{{"scene",
              {{"type", "tension_strip"},
               {"length_m", 0.05},
               {"thickness_m", 0.01},
               {"peak_strain", 0.01}}},
             {"discretization", {{"spacing_m", 0.001}}},
             {"method", tl()}};
    Cell c = make("time_step", label, kTl, job, k > 1.01 ? "fails" : "stable",
                  "explicit time integration beyond its stable step", true);
    c.method_id = "tl_" + id.str();
    std::ostringstream l;
    l << "TL, dt = " << k << " x limit";
    c.method_label = l.str();
    c.job["name"] = "stability time_step / " + c.method_id;
    c.dt_over_limit = k;
    out.push_back(std::move(c));
  }
}

// The gear pair at 3x and 10x the seed paper's speed (full matrix only: the
// paper's model size, 4e-8 s steps over 2 ms).
void gear(std::vector<Cell>& out) {
  for (double k : {3.0, 10.0}) {
    std::ostringstream id;
    id << "gear_" << k << "x_speed";
    auto job = [&](const json& method, const char* contact) {
      json m = method;
      m["contact"] = {{"model", contact}};
      return json{{"scene",
                   {{"type", "rack_pinion"},
                    {"pinion", {{"omega_rad_s", -15.0 * k}}},
                    {"rack", {{"velocity_m_s", -0.353 * k}}}}},
                  // The seed paper's lattice: the study compares the seed paper's
                  // methods, some of which (updated Lagrangian) take one
                  // smoothing length only.
                  {"discretization", {{"particles", "lattice"}}},
                  {"method", m},
                  {"time", {{"end_s", 0.002}}},
                  {"output", history(400)}};
    };
    std::ostringstream label;
    label << "gear pair, " << k << "x speed";
    const char* why = "impact of the teeth at high speed: penetration, contact stability";
    struct C {
      const char* contact;
      const char* mid;
      const char* mlabel;
    };
    for (const C& c : {C{"surface_penalty", "tl_surface_penalty", "TL, contact surface_penalty"},
                       C{"seed_penalty", "tl_seed_penalty", "TL, contact seed_penalty"},
                       C{"hertz", "tl_hertz", "TL, contact hertz"}}) {
      // The seed paper's force and the Hertz-type law act between centres
      // closer than r0 = dx, wider than the 0.1 mm backlash (docs/contact.md).
      const bool centre_reach = std::string(c.contact) != "surface_penalty";
      Cell cell = make(id.str(), label.str(), kTl, job(tl(), c.contact), "stable", why, false);
      cell.method_id = c.mid;
      cell.method_label = c.mlabel;
      cell.job["name"] = "stability " + id.str() + " / " + c.mid;
      cell.criterion = "wedged";
      if (centre_reach) {
        deviates(cell,
                 "the contact reaches r0 = dx, ten times the backlash: the rack tooth is pushed "
                 "from both flanks at once and wedged (forces of 1e5 N, stresses of GPa)");
      }
      out.push_back(std::move(cell));
    }
  }
}

}  // namespace

std::vector<Cell> stability_cells(bool full) {
  std::vector<Cell> cells;
  tension_strip(cells);
  bar_impact(cells);
  plate(cells, false);
  if (full) plate(cells, true);
  spinning_disk(cells, full);
  time_step(cells);
  if (full) gear(cells);
  if (!full) {
    std::erase_if(cells, [](const Cell& c) { return !c.quick; });
  }
  return cells;
}

namespace {

// Time-step cells: the limit is measured on the scene, then the step set to
// a multiple of it (allowed past the limit, as a study must).
json with_step(const Cell& cell, int threads) {
  json job = cell.job;
  if (cell.dt_over_limit <= 0.0) return job;
  const PreparedJob probe = prepare_job(job, threads);
  job["time"]["dt_s"] = cell.dt_over_limit * probe.time_step.dt_limit;
  job["time"]["allow_unstable"] = true;
  return job;
}

}  // namespace

CellRun run_cell(const Cell& cell, int threads) {
  CellRun run;
  run.job = prepare_job(with_step(cell, threads), threads);
  const RunResult rr = run_job(run.job);
  const json& s = rr.summary;
  run.summary = s;
  CellResult& r = run.result;
  const json& health = s.at("health");
  const json& hm = health.at("measures");
  r.energy_drift = s.at("energy").value("drift_relative", 0.0);
  r.energy_growth = hm.at("energy_growth").get<double>();
  r.zigzag = hm.at("zigzag_max").get<double>();
  r.min_spacing_over_dx = hm.at("min_spacing_over_dx").get<double>();
  r.max_penetration_over_dx = hm.at("max_penetration_over_dx").get<double>();
  r.particles = run.job.scene.sim.particles.n;
  r.steps = rr.steps_done;
  r.steps_planned = run.job.steps;
  r.dt_s = run.job.time_step.dt;
  r.dt_limit_s = run.job.time_step.dt_limit;
  r.end_s = run.job.end_s;
  r.wall_s = rr.wall_s;
  r.outcome = health.at("status") == "warning" ? "warning" : "stable";
  if (rr.status == "diverged") {
    r.outcome = "failed";
    r.message = rr.message;
    r.failed_at_s = run.job.scene.sim.time;
    r.failed_at_step = run.job.scene.sim.step;
    r.failed_by = "divergence";
    for (const json& e : health.at("events")) {
      if (e.at("level") == "stop") r.failed_by = e.at("detector").get<std::string>();
    }
    if (r.failed_by == "divergence") {
      // The guard's message names the quantity: non-finite or escape.
      r.failed_by = rr.message.find("left the domain") != std::string::npos ? "escape" : "nan";
    }
  } else if (!health.at("events").empty()) {
    r.message = health.at("events").front().at("message").get<std::string>();
  }
  const json& a = s.at("analysis");
  if (cell.criterion == "stuck" && a.contains("separated")) {
    r.stuck = !a.at("separated").get<bool>();
    if (*r.stuck && r.outcome != "failed") {
      r.outcome = "failed";
      r.failed_by = "stuck";
      r.message = "the bars did not separate after the contact time: adhesion";
    }
  }
  if (cell.criterion == "spurious_stress" && a.contains("von_mises_over_scale")) {
    // validation.md 4: stress of a rigid rotation must stay at the scale of
    // the centrifugal stress; an order above it is spurious.
    constexpr double kSpuriousBound = 0.5;
    r.spurious_stress = a.at("von_mises_over_scale").get<double>();
    if (*r.spurious_stress > kSpuriousBound && r.outcome != "failed") {
      r.outcome = "failed";
      r.failed_by = "spurious_stress";
      std::ostringstream m;
      m.precision(3);
      m << "rigid rotation created von Mises stress " << *r.spurious_stress
        << " x rho omega^2 R^2 (bound " << kSpuriousBound << ")";
      r.message = m.str();
    }
  }
  if (cell.criterion == "wedged" && s.at("model").contains("impact_force_bound_N")) {
    // An elastic mesh never sees more than the load plus the impact of the
    // pitch-line speed mismatch on the mesh spring (rack_pinion.cpp); ten
    // times that means the teeth are pressed into each other from both
    // flanks, which no elastic impact explains.
    constexpr double kWedgedFactor = 10.0;
    const double bound = s.at("model").at("impact_force_bound_N").get<double>();
    r.contact_force_over_bound = s.at("max_contact_force_N").get<double>() / bound;
    if (*r.contact_force_over_bound > kWedgedFactor && r.outcome != "failed") {
      r.outcome = "failed";
      r.failed_by = "wedged";
      std::ostringstream m;
      m.precision(3);
      m << "contact force " << s.at("max_contact_force_N").get<double>() << " N, "
        << *r.contact_force_over_bound << " x what an elastic mesh impact at this speed gives ("
        << bound << " N): a tooth wedged between two";
      r.message = m.str();
    }
  }
  r.as_expected = (cell.expect == "fails") == (r.outcome == "failed");
  r.as_documented = (cell.documented == "fails") == (r.outcome == "failed");
  return run;
}

std::string csv_header() {
  return "case,method,expect,documented,outcome,as_expected,as_documented,failed_by,failed_at_s,"
         "failed_at_step,steps,"
         "steps_planned,dt_s,dt_limit_s,particles,energy_drift,energy_growth,zigzag,"
         "min_spacing_over_dx,max_penetration_over_dx,stuck,spurious_stress,contact_force_over_"
         "bound,"
         "wall_s,message\n";
}

namespace {
std::string quoted(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}
}  // namespace

std::string csv_row(const Cell& c, const CellResult& r) {
  std::ostringstream o;
  o.precision(6);
  o << c.case_id << ',' << c.method_id << ',' << c.expect << ',' << c.documented << ',' << r.outcome
    << ',' << (r.as_expected ? "yes" : "no") << ',' << (r.as_documented ? "yes" : "no") << ','
    << r.failed_by << ',';
  if (r.failed_at_s >= 0) o << r.failed_at_s;
  o << ',';
  if (r.failed_at_step >= 0) o << r.failed_at_step;
  o << ',' << r.steps << ',' << r.steps_planned << ',' << r.dt_s << ',' << r.dt_limit_s << ','
    << r.particles << ',' << r.energy_drift << ',' << r.energy_growth << ',' << r.zigzag << ','
    << r.min_spacing_over_dx << ',' << r.max_penetration_over_dx << ',';
  if (r.stuck) o << (*r.stuck ? "yes" : "no");
  o << ',';
  if (r.spurious_stress) o << *r.spurious_stress;
  o << ',';
  if (r.contact_force_over_bound) o << *r.contact_force_over_bound;
  o << ',' << r.wall_s << ',' << quoted(r.message) << '\n';
  return o.str();
}

json to_json(const Cell& c, const CellResult& r) {
  json j{{"case", c.case_id},
         {"case_label", c.case_label},
         {"method", c.method_id},
         {"method_label", c.method_label},
         {"purpose", c.purpose},
         {"expect", c.expect},
         {"outcome", r.outcome},
         {"as_expected", r.as_expected},
         {"documented", c.documented},
         {"as_documented", r.as_documented},
         {"deviation", c.deviation},
         {"failed_by", r.failed_by},
         {"failed_at_s", r.failed_at_s >= 0 ? json(r.failed_at_s) : json(nullptr)},
         {"failed_at_step", r.failed_at_step >= 0 ? json(r.failed_at_step) : json(nullptr)},
         {"steps", r.steps},
         {"steps_planned", r.steps_planned},
         {"end_s", r.end_s},
         {"dt_s", r.dt_s},
         {"dt_limit_s", r.dt_limit_s},
         {"particles", r.particles},
         {"energy_drift", r.energy_drift},
         {"energy_growth", r.energy_growth},
         {"zigzag", r.zigzag},
         {"min_spacing_over_dx", r.min_spacing_over_dx},
         {"max_penetration_over_dx", r.max_penetration_over_dx},
         {"stuck", r.stuck ? json(*r.stuck) : json(nullptr)},
         {"spurious_stress", r.spurious_stress ? json(*r.spurious_stress) : json(nullptr)},
         {"contact_force_over_bound",
          r.contact_force_over_bound ? json(*r.contact_force_over_bound) : json(nullptr)},
         {"wall_s", r.wall_s},
         {"message", r.message},
         {"job", c.job}};
  return j;
}

}  // namespace gearsph::study
