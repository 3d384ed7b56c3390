#include "solver/run/summary.hpp"

#include <algorithm>
#include <cmath>

#include "solver/diagnostics/energy.hpp"
#include "solver/physics/contact.hpp"
#include "solver/run/runner.hpp"

namespace gearsph {

void PeakTracker::update(const Simulation& sim) {
  const diagnostics::StressPeak p = diagnostics::max_von_mises(sim);
  if (p.particle >= 0 && p.von_mises > von_mises) {
    von_mises = p.von_mises;
    time = sim.time;
    particle = p.particle;
    x = sim.particles.x[p.particle];
    y = sim.particles.y[p.particle];
  }
}

namespace {

nlohmann::json energy_summary(const History& h) {
  nlohmann::json e;
  if (h.rows() == 0) return e;
  const std::vector<double> bal = h.column("energy_balance_J_per_m");
  const std::vector<double> kin = h.column("kinetic_J_per_m");
  const std::vector<double> ela = h.column("elastic_J_per_m");
  double scale = 0.0;
  for (std::size_t r = 0; r < h.rows(); ++r) scale = std::max(scale, kin[r] + ela[r]);
  e["initial_J_per_m"] = bal.front();
  e["final_J_per_m"] = bal.back();
  e["scale_J_per_m"] = scale;
  // Drift of kinetic + elastic + dissipated - work in, relative to the
  // largest mechanical energy of the run.
  e["drift_relative"] = scale > 0 ? (bal.back() - bal.front()) / scale : 0.0;
  e["dissipated_J_per_m"] = h.column("dissipated_J_per_m").back();
  e["drive_work_J_per_m"] = h.column("drive_work_J_per_m").back();
  return e;
}

}  // namespace

nlohmann::json pass_timing(const PassTimes& times, std::int64_t steps) {
  nlohmann::json passes = nlohmann::json::array();
  const double total = times.total_seconds();
  // Seconds over the whole run, from the timed steps (one in kTimedEvery).
  const double scale = times.timed_steps() > 0 ? double(steps) / double(times.timed_steps()) : 0.0;
  for (const PassTime& t : times.entries()) {
    passes.push_back({{"name", t.name},
                      {"seconds", scale * t.seconds},
                      {"share", total > 0.0 ? t.seconds / total : 0.0}});
  }
  return {{"timed_every_steps", PassTimes::kTimedEvery},
          {"timed_steps", times.timed_steps()},
          {"passes", passes}};
}

nlohmann::json make_summary(const PreparedJob& job, const RunResult& result,
                            const PeakTracker& peak) {
  const Scene& scene = job.scene;
  const Simulation& sim = scene.sim;
  nlohmann::json s;
  s["name"] = job.job.at("name");
  s["scene"] = scene.type;
  s["status"] = result.status;
  if (!result.message.empty()) s["message"] = result.message;
  s["particles"] = sim.particles.n;
  nlohmann::json by_body = nlohmann::json::object();
  for (const Body& b : sim.bodies) by_body[b.name] = b.count();
  s["particles_by_body"] = by_body;
  s["steps"] = result.steps_done;
  s["steps_planned"] = job.steps;
  s["dt_s"] = sim.dt;
  s["end_s"] = job.end_s;
  s["simulated_s"] = sim.time;
  s["wall_s"] = result.wall_s;
  s["threads"] = sim.threads;
  s["timing"] = pass_timing(sim.pass_times, result.steps_done);
  s["particle_steps_per_s"] =
      result.wall_s > 0 ? double(sim.particles.n) * double(result.steps_done) / result.wall_s : 0.0;
  s["time_step"] = {{"dt_s", job.time_step.dt},
                    {"dt_limit_s", job.time_step.dt_limit},
                    {"courant", job.time_step.courant},
                    {"courant_limit", job.time_step.courant_limit},
                    {"signal_speed_m_s", job.time_step.signal_speed},
                    {"limited_by", job.time_step.limited_by},
                    {"chosen_by", job.time_step.chosen_by}};
  s["max_von_mises_Pa"] = peak.von_mises;
  s["max_von_mises_time_s"] = peak.time;
  if (peak.particle >= 0) {
    s["max_von_mises_particle"] = peak.particle;
    s["max_von_mises_body"] = sim.bodies[sim.particles.body[peak.particle]].name;
    s["max_von_mises_position_m"] = {peak.x, peak.y};
  }
  s["energy"] = energy_summary(result.history);
  const diagnostics::Momentum m = diagnostics::momentum(sim);
  s["momentum_final_kg_m_s"] = {m.px, m.py};
  const NeighbourList& nl = sim.neighbours;
  s["neighbours"] = {{"list_builds", nl.builds()},
                     {"entries_per_particle",
                      sim.particles.n ? double(std::max(nl.entries(), sim.reference.entries())) /
                                            double(sim.particles.n)
                                      : 0.0}};
  s["model"] = scene.description;
  s["method"] = job.job.at("method");
  // What the contact's spread became where the job left it to the scene.
  if (physics::contact_smoothing(sim)) {
    auto& contact = s["method"]["contact"];
    contact["smoothing_spacings"] = sim.contact.smoothing_spacings;
    nlohmann::json scale = nlohmann::json::object();
    for (const Body& b : sim.bodies) scale[b.name] = b.contact_spread_scale;
    contact["spread_scale_by_body"] = scale;
  }
  // Graded particles: the finest spacing beside the bulk's, which h_m is
  // taken at (each particle's h is h_over_dx times its own spacing).
  double finest = sim.discretization.dx;
  for (std::size_t i = 0; i < sim.particles.n; ++i) {
    if (sim.particles.spacing[i] > 0.0) finest = std::min(finest, sim.particles.spacing[i]);
  }
  s["discretization"] = {{"spacing_m", sim.discretization.dx},
                         {"finest_spacing_m", finest},
                         {"h_over_dx", sim.discretization.h_over_dx},
                         {"h_m", sim.h()},
                         {"kernel", kernel_name(sim.discretization.kernel)}};
  s["analysis"] = scene.analyse ? scene.analyse(result.history, sim) : nlohmann::json::object();
  // Scenes may promote some results to stable top-level keys.
  if (s["analysis"].contains("summary_fields")) {
    for (auto& [key, value] : s["analysis"]["summary_fields"].items()) s[key] = value;
    s["analysis"].erase("summary_fields");
  }
  return s;
}

}  // namespace gearsph
