#include "solver/study/speed_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "solver/job/job_size.hpp"

namespace gearsph::study {

namespace {

using json = nlohmann::json;
namespace dyn = gear::dynamics;
constexpr double kPi = std::numbers::pi;
// The steady-mesh detector's reference (diagnostics::SteadyMeshOptions)
// comes on top of the steady periods asked for.
constexpr int kReferencePeriods = 3;

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

double median(std::vector<double> v) {
  if (v.empty()) return -1.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The analysis.dynamics number of a summary, NaN where it has none.
double dynamics_value(const json& summary, const char* key) {
  if (!summary.is_object()) return std::nan("");
  const json* a = &summary;
  for (const char* k : {"analysis", "dynamics"}) {
    if (!a->contains(k)) return std::nan("");
    a = &a->at(k);
  }
  return a->contains(key) && a->at(key).is_number() ? a->at(key).get<double>() : std::nan("");
}

// The peak of K_v within [lo, hi] of the mesh frequency (null: fewer than
// three speeds there). The band around f_n keeps the primary resonance
// apart from the super-harmonic at f_n / 2 and the principal parametric
// resonance at 2 f_n, which the two-level stiffness also drives.
json peak_in_band(const std::vector<double>& f, const std::vector<double>& kv, double lo,
                  double hi) {
  std::vector<double> x, y;
  for (std::size_t k = 0; k < f.size() && k < kv.size(); ++k) {
    if (f[k] >= lo && f[k] <= hi) {
      x.push_back(f[k]);
      y.push_back(kv[k]);
    }
  }
  return x.size() >= 3 ? json(dyn::peak_abscissa(x, y)) : json();
}

json finite_or_null(double v) {
  return std::isfinite(v) ? json(v) : json(nullptr);
}

}  // namespace

std::vector<double> default_sweep_ratios() {
  return {0.2, 0.4, 0.6, 0.8, 0.9, 1.0, 1.1, 1.25, 1.5, 2.0};
}

SpeedSweepRequest read_speed_sweep(const json& request) {
  std::vector<JobIssue> issues;
  SpeedSweepRequest out;
  if (!request.is_object() || !request.contains("job") || !request.at("job").is_object()) {
    throw InvalidJob(
        std::vector<JobIssue>{{"/job", "a speed sweep needs the job it runs at each speed"}});
  }
  try {
    out.job = validate_job(request.at("job"));
  } catch (const InvalidJob& e) {
    for (const JobIssue& i : e.issues) issues.push_back({"/job" + i.pointer, i.message});
    throw InvalidJob(issues);
  }
  const json& s = out.job.at("scene");
  const std::string type = s.at("type").get<std::string>();
  if (type != "rack_pinion") {
    issues.push_back({"/job/scene/type", "a speed sweep runs a rack_pinion job; this one is a " +
                                             type + " scene, which has no mesh to sweep"});
  } else {
    if (s.at("quasi_static").get<bool>()) {
      issues.push_back({"/job/scene/quasi_static",
                        "a speed sweep needs a dynamic run; a quasi-static check has no speed"});
    }
    if (!(s.at("rack").at("load_N").get<double>() > 0.0)) {
      issues.push_back({"/job/scene/rack/load_N",
                        "a speed sweep needs a loaded mesh: with no rack load the teeth carry "
                        "no mean force to take K_v = peak / mean against"});
    }
    if (s.at("pinion").contains("torque_N_m")) {
      issues.push_back({"/job/scene/pinion/torque_N_m",
                        "a speed sweep holds the pinion at each speed; a torque-driven pinion "
                        "would not stay at it"});
    }
  }
  const json ratios = request.value("ratios", json(default_sweep_ratios()));
  if (!ratios.is_array() || ratios.empty()) {
    issues.push_back({"/ratios",
                      "give at least one speed ratio (mesh frequency over the lumped "
                      "model's natural frequency)"});
  } else {
    for (std::size_t k = 0; k < ratios.size(); ++k) {
      const json& r = ratios[k];
      if (!r.is_number() || !(r.get<double>() > 0.0) || !std::isfinite(r.get<double>())) {
        issues.push_back({"/ratios/" + std::to_string(k),
                          "a speed ratio must be a positive number (the mesh frequency over the "
                          "lumped model's natural frequency); got " +
                              r.dump()});
      } else {
        out.ratios.push_back(r.get<double>());
      }
    }
  }
  const json periods = request.value("steady_periods", json(20));
  if (!periods.is_number_integer() || periods.get<int>() < 1 || periods.get<int>() > 1000) {
    issues.push_back({"/steady_periods",
                      "the steady mesh periods per speed must be a whole "
                      "number from 1 to 1000"});
  } else {
    out.steady_periods = periods.get<int>();
  }
  // ISO's two levels by default: the measured cycle's single-contact checks
  // are not yet clean (docs/dynamics.md, "The measured stiffness").
  const json stiffness = request.value("stiffness", json("iso"));
  if (stiffness.is_object()) {
    // A table: the positions over the mesh cycle and a stiffness at each.
    try {
      out.given_stiffness =
          mesh_cycle_table(stiffness.at("position").get<std::vector<double>>(),
                           stiffness.at("stiffness_N_m").get<std::vector<double>>());
      out.stiffness = "given";
    } catch (const std::exception& e) {
      issues.push_back({"/stiffness",
                        "a given stiffness is {\"position\": [s, ...], \"stiffness_N_m\": [k, "
                        "...]}: at least two positions ascending within [0, 1) of the mesh "
                        "cycle, a positive stiffness each (a measured cycle's "
                        "stiffness_cycle.json is one); " +
                            std::string(e.what())});
    }
  } else if (stiffness != "measured" && stiffness != "iso") {
    issues.push_back({"/stiffness",
                      "the lumped model's mesh stiffness is \"measured\" (quasi-static checks "
                      "of the same pair over a mesh cycle), \"iso\" (ISO 6336-1's two "
                      "levels) or a table {\"position\": [...], \"stiffness_N_m\": [...]}; got " +
                          stiffness.dump()});
  } else {
    out.stiffness = stiffness.get<std::string>();
  }
  const json positions = request.value("stiffness_positions", json(kDefaultCyclePositions));
  if (!positions.is_number_integer() || positions.get<int>() < 2 || positions.get<int>() > 64) {
    issues.push_back({"/stiffness_positions",
                      "the mesh cycle's static checks must be a whole number from 2 to 64"});
  } else {
    out.stiffness_positions = positions.get<int>();
  }
  if (!issues.empty()) throw InvalidJob(issues);
  return out;
}

json plan_document(const SpeedSweepPlan& p) {
  const SpeedSweepRequest& r = p.request;
  return {{"request",
           {{"job", r.job},
            {"ratios", r.ratios},
            {"steady_periods", r.steady_periods},
            {"stiffness", r.stiffness},
            {"given_stiffness",
             {{"position", r.given_stiffness.position}, {"value", r.given_stiffness.value}}},
            {"stiffness_positions", r.stiffness_positions}}},
          {"lumped_model", p.lumped_model},
          {"stiffness", {{"position", p.stiffness.position}, {"value", p.stiffness.value}}},
          {"stiffness_from", p.stiffness_from},
          {"stiffness_cycle", p.stiffness_cycle},
          {"natural_frequency_Hz", p.natural_frequency_Hz},
          {"iso_resonance_Hz", p.iso_resonance_Hz},
          {"mesh_frequency_Hz", p.mesh_frequency_Hz},
          {"jobs", p.jobs},
          {"particle_steps", p.particle_steps},
          {"transient_allowance_s", p.transient_allowance_s}};
}

SpeedSweepPlan plan_from_document(const json& d) {
  SpeedSweepPlan p;
  const json& r = d.at("request");
  p.request.job = r.at("job");
  p.request.ratios = r.at("ratios").get<std::vector<double>>();
  p.request.steady_periods = r.at("steady_periods").get<int>();
  p.request.stiffness = r.at("stiffness").get<std::string>();
  p.request.stiffness_positions = r.at("stiffness_positions").get<int>();
  p.request.given_stiffness.position =
      r.at("given_stiffness").at("position").get<std::vector<double>>();
  p.request.given_stiffness.value = r.at("given_stiffness").at("value").get<std::vector<double>>();
  p.lumped_model = d.at("lumped_model");
  p.stiffness.position = d.at("stiffness").at("position").get<std::vector<double>>();
  p.stiffness.value = d.at("stiffness").at("value").get<std::vector<double>>();
  p.stiffness_from = d.at("stiffness_from").get<std::string>();
  p.stiffness_cycle = d.at("stiffness_cycle");
  p.natural_frequency_Hz = d.at("natural_frequency_Hz").get<double>();
  p.iso_resonance_Hz = d.at("iso_resonance_Hz").get<double>();
  p.mesh_frequency_Hz = d.at("mesh_frequency_Hz").get<std::vector<double>>();
  p.jobs = d.at("jobs").get<std::vector<json>>();
  p.particle_steps = d.at("particle_steps").get<std::vector<double>>();
  p.transient_allowance_s = d.at("transient_allowance_s").get<double>();
  return p;
}

dyn::SdofModel sdof_from_description(const json& lm, double zeta) {
  return sdof_from_description(
      lm, zeta,
      dyn::two_level_stiffness(lm.at("single_pair_stiffness_N_m").get<double>(),
                               lm.at("double_pair_stiffness_N_m").get<double>(),
                               lm.at("contact_ratio").get<double>()));
}

dyn::SdofModel sdof_from_description(const json& lm, double zeta,
                                     const dyn::MeshCycleTable& stiffness) {
  dyn::SdofModel m;
  m.mass_kg = lm.at("mass_on_line_of_action_kg").get<double>();
  m.stiffness = stiffness;
  m.damping_ratio = zeta;
  m.backlash_m = lm.at("backlash_along_line_of_action_m").get<double>();
  m.load_N = lm.at("load_along_line_of_action_N").get<double>();
  return m;
}

SpeedSweepPlan plan_speed_sweep(const SpeedSweepRequest& req, const SweepLimits& limits,
                                double transient_natural_periods,
                                const MeshStiffnessCycle* measured, int threads) {
  SpeedSweepPlan plan;
  plan.request = req;
  if (static_cast<int>(req.ratios.size()) > limits.max_jobs) {
    throw InvalidJob(
        std::vector<JobIssue>{{"/ratios", std::to_string(req.ratios.size()) +
                                              " speeds would make as many jobs; at most " +
                                              std::to_string(limits.max_jobs) + " are allowed"}});
  }
  const double r_max = *std::max_element(req.ratios.begin(), req.ratios.end());
  // The longest run in mesh periods: the transient allowance (natural
  // periods are r mesh periods) and the steady periods with the reference.
  const double periods_max =
      transient_natural_periods * r_max + req.steady_periods + kReferencePeriods + 1;
  json base = req.job;
  json& s = base["scene"];
  s["pinion"]["modelled_teeth"] = "all";
  // The rack's travel over the longest run, plus the engagement window.
  s["rack"]["modelled_teeth"] = static_cast<int>(std::ceil(periods_max)) + 3;
  base["output"]["frames"] = 0;
  // Each speed ends once its steady mesh has lasted the periods asked for
  // (Scene::ends_early): a speed runs no longer than it needs.
  s["steady_mesh_periods"] = req.steady_periods;
  // The masses (and so the natural frequency) do not depend on the speed
  // once the modelled teeth are fixed: one short build gives them.
  json probe = base;
  probe["time"]["end_s"] = 1e-5;
  const PreparedJob prepared = prepare_job(probe, 1);
  plan.lumped_model = prepared.scene.description.at("lumped_model");
  if (!plan.lumped_model.contains("natural_frequency_Hz")) {
    throw InvalidJob(std::vector<JobIssue>{
        {"/job/scene/pinion", plan.lumped_model.value("note", std::string("no lumped model"))}});
  }
  plan.stiffness_from = req.stiffness;
  if (req.stiffness == "given") {
    plan.stiffness = req.given_stiffness;
    plan.stiffness_cycle = {{"position", req.given_stiffness.position},
                            {"stiffness_N_m", req.given_stiffness.value}};
  } else if (req.stiffness == "measured") {
    const MeshStiffnessCycle cycle =
        measured ? *measured : mesh_stiffness_cycle(req.job, req.stiffness_positions, threads);
    plan.stiffness = cycle.table;
    plan.stiffness_cycle = describe_stiffness_cycle(cycle);
  } else {
    plan.stiffness = sdof_from_description(plan.lumped_model, 0.0).stiffness;
  }
  plan.natural_frequency_Hz = dyn::natural_frequency_Hz(
      plan.stiffness.mean(), plan.lumped_model.at("mass_on_line_of_action_kg").get<double>());
  if (plan.lumped_model.contains("iso6336_1_method_b")) {
    plan.iso_resonance_Hz =
        plan.lumped_model.at("iso6336_1_method_b").at("resonance_mesh_Hz").get<double>();
  }
  const int z = s.at("pinion").at("teeth").get<int>();
  const double r_p = 0.5e-3 * s.at("pinion").at("module_mm").get<double>() * z;
  const double sign = s.at("pinion").at("omega_rad_s").get<double>() > 0.0 ? 1.0 : -1.0;
  const double f_n = plan.natural_frequency_Hz;
  plan.transient_allowance_s = transient_natural_periods / f_n;
  std::vector<JobIssue> issues;
  for (std::size_t k = 0; k < req.ratios.size(); ++k) {
    const double f = req.ratios[k] * f_n;
    const double omega = sign * 2.0 * kPi * f / z;
    json job = base;
    job["name"] = base.value("name", std::string("job")) + "-speed-" + number(req.ratios[k]);
    job["scene"]["pinion"]["omega_rad_s"] = omega;
    job["scene"]["rack"]["velocity_m_s"] = omega * r_p;  // the pitch line's speed
    const double end_s =
        plan.transient_allowance_s + (req.steady_periods + kReferencePeriods + 1) / f;
    job["time"]["end_s"] = end_s;
    // Samples to resolve the ringing and the mesh: 40 a period of the faster.
    const double points = std::ceil(end_s * std::max(f_n, f) * 40.0);
    job["output"]["history_points"] = static_cast<std::int64_t>(std::clamp(points, 10.0, 1e6));
    const std::string where = "/ratios/" + std::to_string(k);
    json valid;
    try {
      valid = validate_job(job);
    } catch (const InvalidJob& e) {
      // A speed the job's schema refuses (a rack faster than it allows).
      for (const JobIssue& i : e.issues) {
        issues.push_back({where, "the job at this speed (" + number(f) +
                                     " Hz mesh frequency) is refused at " + i.pointer + ": " +
                                     i.message});
      }
      continue;
    }
    const JobSize size = estimate_job_size(valid);
    const double work = size.particles * size.steps;
    if (size.particles > limits.max_particles || size.steps > limits.max_steps ||
        work > limits.max_particle_steps) {
      issues.push_back({where, "the job at this speed (" + number(f) + " Hz mesh frequency, " +
                                   number(end_s) + " s) needs " + number(size.particles) +
                                   " particles and " + number(size.steps) + " steps (" +
                                   number(work) + " particle-steps); the limits are " +
                                   number(limits.max_particles) + ", " + number(limits.max_steps) +
                                   " and " + number(limits.max_particle_steps)});
    }
    plan.mesh_frequency_Hz.push_back(f);
    plan.jobs.push_back(job);
    plan.particle_steps.push_back(work);
  }
  if (!issues.empty()) throw InvalidJob(issues);
  return plan;
}

json sweep_report(const SpeedSweepPlan& plan, const std::vector<json>& summaries,
                  double fallback_zeta) {
  // The speeds in ascending order.
  std::vector<std::size_t> order(plan.mesh_frequency_Hz.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return plan.mesh_frequency_Hz[a] < plan.mesh_frequency_Hz[b];
  });
  std::vector<double> f, zetas;
  json kv_sph = json::array(), dte_sph = json::array(), loss_sph = json::array();
  json steady = json::array(), wall = json::array(), work = json::array(), end = json::array();
  std::vector<double> f_ran, kv_ran;
  for (std::size_t k : order) {
    f.push_back(plan.mesh_frequency_Hz[k]);
    const json& s = k < summaries.size() ? summaries[k] : json(nullptr);
    const double kv = dynamics_value(s, "K_v");
    kv_sph.push_back(finite_or_null(kv));
    dte_sph.push_back(finite_or_null(dynamics_value(s, "dte_pp_m")));
    loss_sph.push_back(finite_or_null(dynamics_value(s, "contact_loss_fraction")));
    steady.push_back(s.is_object() && s.contains("analysis") && s["analysis"].contains("dynamics")
                         ? s["analysis"]["dynamics"].value("steady", false)
                         : false);
    wall.push_back(s.is_object() ? s.value("wall_s", 0.0) : 0.0);
    work.push_back(plan.particle_steps[k]);
    end.push_back(plan.jobs[k].at("time").at("end_s"));
    if (std::isfinite(kv)) {
      f_ran.push_back(f.back());
      kv_ran.push_back(kv);
    }
    if (s.is_object() && s.contains("analysis") && s["analysis"].contains("dynamics")) {
      const double z = s["analysis"]["dynamics"]["ringing"].value("damping_ratio", -1.0);
      if (z > 0.0) zetas.push_back(z);
    }
  }
  const double zeta = zetas.empty() ? fallback_zeta : median(zetas);
  const dyn::SdofModel model = sdof_from_description(plan.lumped_model, zeta, plan.stiffness);
  // Up the sweep's speeds, and down them: where they differ, the jump.
  const std::vector<dyn::SdofResponse> up = dyn::sweep(model, f);
  const std::vector<double> f_down(f.rbegin(), f.rend());
  const std::vector<dyn::SdofResponse> down = dyn::sweep(model, f_down);
  json kv_sdof = json::array(), dte_sdof = json::array(), loss_sdof = json::array(),
       kv_sdof_down = json::array();
  for (std::size_t k = 0; k < f.size(); ++k) {
    kv_sdof.push_back(up[k].K_v);
    dte_sdof.push_back(up[k].dte_pp_m);
    loss_sdof.push_back(up[k].contact_loss_fraction);
    kv_sdof_down.push_back(down[f.size() - 1 - k].K_v);
  }
  // The lumped model's resonance on a fine sweep over the same range.
  std::vector<double> fine, kv_fine;
  const double lo = f.front(), hi = f.back();
  for (int k = 0; k <= 200; ++k) fine.push_back(lo + (hi - lo) * k / 200.0);
  for (const dyn::SdofResponse& r : dyn::sweep(model, fine)) kv_fine.push_back(r.K_v);
  // The same model on ISO's two levels, for comparison with the measured
  // table.
  const dyn::SdofModel iso_model = sdof_from_description(plan.lumped_model, zeta);
  std::vector<double> kv_fine_iso;
  for (const dyn::SdofResponse& r : dyn::sweep(iso_model, fine)) kv_fine_iso.push_back(r.K_v);
  const double f_n_iso = plan.lumped_model.at("natural_frequency_Hz").get<double>();
  json ratios = json::array();
  for (double fk : f) ratios.push_back(fk / plan.natural_frequency_Hz);
  return {{"mesh_frequency_Hz", f},
          {"ratio_to_natural_frequency", ratios},
          {"K_v_sph", kv_sph},
          {"K_v_sdof", kv_sdof},
          {"K_v_sdof_down", kv_sdof_down},
          {"dte_pp_m_sph", dte_sph},
          {"dte_pp_m_sdof", dte_sdof},
          {"contact_loss_fraction_sph", loss_sph},
          {"contact_loss_fraction_sdof", loss_sdof},
          {"steady_sph", steady},
          {"wall_s_sph", wall},
          {"planned_particle_steps", work},
          {"planned_end_s", end},
          {"transient_allowance_s", plan.transient_allowance_s},
          {"resonance_Hz_sph", peak_in_band(f_ran, kv_ran, 0.5 * plan.natural_frequency_Hz,
                                            1.5 * plan.natural_frequency_Hz)},
          {"resonance_Hz_sdof", peak_in_band(fine, kv_fine, 0.5 * plan.natural_frequency_Hz,
                                             1.5 * plan.natural_frequency_Hz)},
          {"largest_K_v_Hz_sdof", dyn::peak_abscissa(fine, kv_fine)},
          {"resonance_Hz_iso", plan.iso_resonance_Hz > 0.0 ? json(plan.iso_resonance_Hz) : json()},
          {"natural_frequency_Hz_sdof", plan.natural_frequency_Hz},
          {"stiffness_from", plan.stiffness_from},
          {"stiffness_table",
           {{"position", plan.stiffness.position},
            {"stiffness_N_m", plan.stiffness.value},
            {"mean_N_m", plan.stiffness.mean()},
            {"measured", plan.stiffness_cycle}}},
          {"iso_stiffness_sdof",
           {{"natural_frequency_Hz", f_n_iso},
            {"mean_stiffness_N_m", iso_model.stiffness.mean()},
            {"resonance_Hz", peak_in_band(fine, kv_fine_iso, 0.5 * f_n_iso, 1.5 * f_n_iso)},
            {"K_v_fine", kv_fine_iso},
            {"note",
             "the lumped model on ISO 6336-1's two levels (c', 1.75 c') over the same "
             "speeds, beside the table it used"}}},
          {"mesh_frequency_Hz_fine", fine},
          {"K_v_sdof_fine", kv_fine},
          {"damping_ratio",
           {{"value", zeta},
            {"from", zetas.empty() ? "assumed (no SPH run's ringing was measured)"
                                   : "median of the SPH runs' ringing (log decrement)"},
            {"measured", zetas}}},
          {"lumped_model", plan.lumped_model},
          {"resonance_definition",
           "the mesh frequency of the largest K_v between 0.5 and 1.5 times the lumped model's "
           "natural frequency (the primary resonance; the super-harmonic at f_n / 2 and the "
           "parametric resonance at 2 f_n lie outside), refined by a parabola through its "
           "neighbours; largest_K_v_Hz_sdof: the largest over the whole sweep"}};
}

}  // namespace gearsph::study
