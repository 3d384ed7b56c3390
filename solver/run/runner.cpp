#include "solver/run/runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "solver/diagnostics/energy.hpp"
#include "solver/diagnostics/guard.hpp"
#include "solver/diagnostics/health.hpp"
#include "solver/integrate/integrator.hpp"
#include "solver/run/summary.hpp"
#include "solver/run/thread_trial.hpp"

namespace gearsph {

namespace {

using Clock = std::chrono::steady_clock;
// The health check's pair-loop detectors (particle disorder, zig-zag) run
// at the history samples at most this often: disorder and zig-zag build up
// over tens of steps, and the stability tests see every failure at this
// cadence (tests/test_stability_detectors.cpp); the energy, which can run
// away within a few steps, is checked at every sample.
constexpr std::int64_t kHealthEverySteps = 10;

// The columns every run records, then the scene's own.
History make_history(const Scene& scene) {
  std::vector<std::string> cols = {"time_s",
                                   "max_von_mises_Pa",
                                   "kinetic_J_per_m",
                                   "elastic_J_per_m",
                                   "dissipated_J_per_m",
                                   "drive_work_J_per_m",
                                   "energy_balance_J_per_m",
                                   "momentum_x_kg_m_s",
                                   "momentum_y_kg_m_s"};
  if (scene.sim.bodies.size() > 1) {
    cols.push_back("contact_pairs");
    cols.push_back("max_penetration_m");
    for (const Body& b : scene.sim.bodies) cols.push_back("contact_force_" + b.name + "_N_per_m");
  }
  for (const HistoryColumn& c : scene.columns) cols.push_back(c.name);
  return History(cols);
}

// One history row; returns the energy it found, which the health check
// reads too.
diagnostics::EnergyState sample(const Scene& scene, History& history, std::vector<double>& row) {
  const Simulation& sim = scene.sim;
  const diagnostics::EnergyState e = diagnostics::energy(sim);
  const diagnostics::Momentum m = diagnostics::momentum(sim);
  row.clear();
  row.push_back(sim.time);
  row.push_back(diagnostics::max_von_mises(sim).von_mises);
  row.push_back(e.kinetic);
  row.push_back(e.elastic);
  row.push_back(e.dissipated);
  row.push_back(e.drive_work);
  row.push_back(e.total());
  row.push_back(m.px);
  row.push_back(m.py);
  if (sim.bodies.size() > 1) {
    const ContactState& cs = sim.contact_state;
    row.push_back(static_cast<double>(cs.active_pairs));
    row.push_back(cs.max_penetration);
    for (std::size_t b = 0; b < sim.bodies.size(); ++b) {
      row.push_back(b < cs.force_x.size() ? std::hypot(cs.force_x[b], cs.force_y[b]) : 0.0);
    }
  }
  for (const HistoryColumn& c : scene.columns) row.push_back(c.value(sim));
  history.add_row(row);
  return e;
}

}  // namespace

RunResult run_job(PreparedJob& job, RunObserver* observer) {
  Scene& scene = job.scene;
  Simulation& sim = scene.sim;
  RunResult result;
  result.history = make_history(scene);
  result.history.reserve_rows(static_cast<std::size_t>(job.steps / job.history_every + 2));
  PeakTracker peak;
  std::vector<double> row;
  // The run's own health check (diagnostics/health.hpp), at the history samples.
  diagnostics::HealthMonitor health(
      diagnostics::read_health_limits(job.job.value("health", nlohmann::json::object())));

  const auto start = Clock::now();
  auto wall = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  ThreadTrial trial;
  nlohmann::json switches = nlohmann::json::array();  // the repeated trials' switches
  double next_trial_s = 0.0;
  if (job.threads_by == "trial") {
    trial = trial_threads(sim, job.trial_threads);
    sim.threads = trial.chosen;
    next_trial_s = wall() + job.retrial_every_s;
  }
  // The trial again on a copy of the run as it is now; from the next step
  // on, the count it gives (threads_after_retrial).
  auto retrial = [&](std::int64_t s) {
    const ThreadTrial again = trial_threads(sim, job.trial_threads);
    next_trial_s = wall() + job.retrial_every_s;
    const int next = threads_after_retrial(again, sim.threads);
    if (next == sim.threads) return;
    sim.threads = next;
    switches.push_back({{"step", s + 1}, {"threads", next}, {"us_per_step", again.us_per_step}});
  };
  if (observer) observer->on_start(job);
  auto last_progress = Clock::now();

  try {
    integrate::initialise(sim);
    peak.update(sim);
    health.check(sim);
    sample(scene, result.history, row);
    std::int64_t frame = 0, last_health = 0;
    if (observer) {
      observer->on_sample(sim, result.history);
      if (job.snapshot_every > 0) observer->on_snapshot(sim, frame++);
    }
    // The last step of the run: job.steps, moved on by each quasi-static
    // stage the scene asks for (Scene::next_stage).
    std::int64_t last = job.steps;
    for (std::int64_t s = 1; s <= last; ++s) {
      integrate::step(sim);
      peak.update(sim);
      if (s % job.history_every == 0 || s == last) {
        diagnostics::check_health(sim);
        const diagnostics::EnergyState e = sample(scene, result.history, row);
        // The energy at every sample, the detectors that loop over pairs at
        // most every kHealthEverySteps: a short run sampling every step
        // spent 7 % of its time in them (docs/speed-accuracy-history.md, "Outputs").
        const bool full = s - last_health >= kHealthEverySteps || s == last;
        health.check(sim, e, full);
        if (full) last_health = s;
        if (observer) observer->on_sample(sim, result.history);
        if (scene.ends_early) result.ended_early = scene.ends_early(result.history);
      }
      const bool ending = !result.ended_early.empty();
      if (observer && job.snapshot_every > 0 &&
          (s % job.snapshot_every == 0 || s == last || ending)) {
        observer->on_snapshot(sim, frame++);
      }
      result.steps_done = s;
      if (ending) break;
      if (s == last && scene.next_stage) {
        const double before = diagnostics::energy(sim).total();
        const double more_s = scene.next_stage(sim);
        if (more_s > 0.0) {
          integrate::initialise(sim);  // the pairs the stage changed, on the state reached
          // The strain energy a crack's advance released leaves the
          // mechanical energy, as the viscosity's work does: booked with it,
          // so that the balance (and the health check on it) stays level.
          sim.energy.dissipated += before - diagnostics::energy(sim).total();
          last += std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(more_s / sim.dt)));
        }
      }
      if ((s & 63) == 0 && job.threads_by == "trial" && s < last && wall() >= next_trial_s) {
        retrial(s);
      }
      if ((s & 63) == 0 && observer) {
        if (observer->cancelled()) {
          result.status = "cancelled";
          result.message = "cancelled at step " + std::to_string(s);
          break;
        }
        const auto now = Clock::now();
        if (now - last_progress > std::chrono::milliseconds(500)) {
          last_progress = now;
          Progress p{s, last, sim.time, job.end_s, wall(), 0.0};
          p.eta_s = p.wall_s * (1.0 / p.fraction() - 1.0);
          observer->on_progress(p);
        }
      }
    }
  } catch (const DivergenceError& e) {
    result.status = "diverged";
    result.message = e.what();
  }
  result.wall_s = wall();
  if (observer) {
    Progress p{result.steps_done, job.steps, sim.time, job.end_s, result.wall_s, 0.0};
    observer->on_progress(p);
  }
  if (result.status == "completed" && !health.events().empty()) {
    result.message = "completed with health warnings: " + health.events().front().message;
  }
  result.summary = make_summary(job, result, peak);
  result.summary["threads_by"] = job.threads_by;
  if (!result.ended_early.empty()) result.summary["ended_early"] = result.ended_early;
  if (!trial.threads.empty()) {
    result.summary["thread_trial"] = {{"threads", trial.threads},
                                      {"us_per_step", trial.us_per_step},
                                      {"chosen", trial.chosen},
                                      {"switches", switches}};
  }
  result.summary["health"] = health.report();
  result.summary["warnings"] = health.warnings();
  // What the scene's analysis found amiss in a run that completed (a static
  // check whose tooth 0 carries no load).
  if (result.summary.contains("analysis") && result.summary["analysis"].contains("warnings")) {
    for (const nlohmann::json& w : result.summary["analysis"]["warnings"]) {
      result.summary["warnings"].push_back(w);
    }
  }
  if (observer) observer->on_finish(job, result);
  return result;
}

}  // namespace gearsph
