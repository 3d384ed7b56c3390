// POST /preview: a job document in, the scene it would build out, without
// storing or running anything: each body's particle count, the outlines
// and modelled teeth, the particles themselves (for small scenes), the time
// step and number of steps, and a run-time estimate. The dashboard draws
// its geometry preview from this. A job POST /jobs would refuse is
// answered with `accepted: false` and the same errors, at the same pointers.
#include "server/routes_preview.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <utility>

#include "server/documents.hpp"
#include "server/fe_stage_estimate.hpp"
#include "server/job_limits.hpp"
#include "server/log.hpp"
#include "server/problem.hpp"
#include "server/submission.hpp"
#include "solver/job/job.hpp"
#include "solver/job/job_size.hpp"

namespace gearsph::server::routes {

namespace {

// Particles are listed in the answer up to this many (about 40 bytes each).
constexpr std::size_t kMaxListedParticles = 20000;
// Jobs whose measured speed the estimate averages: the most recent ones.
constexpr std::int64_t kSpeedSampleJobs = 20;
// Runs shorter than this are mostly start-up and would understate the speed.
constexpr double kMinSampleWall_s = 1.0;
// Used when neither a finished job nor the calibration gives a speed: the
// rack-and-pinion case (651 particles, total Lagrangian, 2 threads) on a
// 2-core machine ran at 4.8e4 particle-steps per second.
constexpr double kFallbackParticleStepsPerSecond = 5e4;

double rounded(double v, double quantum) {
  return std::round(v / quantum) * quantum;
}

// The run time: the particle-steps at the speed of this server's recent
// successful jobs (their output and FE time taken off), plus the time to
// write this job's frames and histories, plus its FE check's
// (fe_stage_estimate.hpp) when it asks for one.
nlohmann::json run_time_estimate(Services& s, const JobEstimate& estimate, bool fe_check) {
  JobQuery q;
  q.statuses = {JobStatus::successful};
  q.limit = kSpeedSampleJobs;
  double work = 0, wall = 0;
  int used = 0;
  for (const JobRecord& j : s.store.jobs(q).jobs) {
    if (j.wall_s < kMinSampleWall_s || j.steps <= 0 || j.particles <= 0) continue;
    const auto job = nlohmann::json::parse(j.job_json, nullptr, false);
    const double output = job.is_object() ? output_seconds_of(job, j.particles, j.steps) : 0.0;
    // A run that mostly wrote output says little about computing: its
    // compute time is taken as at least a tenth of its wall time.
    const double sph_wall =
        stage_wall(j.wall_s, fe_check_member(j, j.fe_check_json)).at("sph").get<double>();
    work += static_cast<double>(j.particles) * static_cast<double>(j.steps);
    wall += std::max(sph_wall - output, 0.1 * sph_wall);
    ++used;
  }
  const bool measured = used > 0 && wall > 0 && work > 0;
  // Before a finished job: the speed this server measured of itself.
  const SpeedCalibration& calibration = measured ? SpeedCalibration{} : s.calibration();
  const bool calibrated = !measured && calibration.particle_steps_per_s > 0;
  const double speed = measured     ? work / wall
                       : calibrated ? calibration.particle_steps_per_s
                                    : kFallbackParticleStepsPerSecond;
  const double compute_s = estimate.particle_steps / speed;
  const std::optional<FeStageEstimate> fe =
      fe_check ? std::optional(estimate_fe_stage(s.store)) : std::nullopt;
  nlohmann::json e = {
      {"wall_s", compute_s + estimate.output_s + (fe ? fe->seconds : 0.0)},
      {"sph_s", compute_s + estimate.output_s},
      {"fe_check_s", fe ? nlohmann::json(fe->seconds) : nlohmann::json(nullptr)},
      {"compute_s", compute_s},
      {"output_s", estimate.output_s},
      {"particle_steps_per_s", speed},
      {"basis", measured     ? "measured"
                : calibrated ? "calibrated"
                             : "fallback"},
      {"jobs_measured", used},
      {"threads_per_job", s.config.threads_per_job},
  };
  char note[320];
  if (measured) {
    std::snprintf(note, sizeof note,
                  "estimate: %.3g particle-steps per second, the mean of this server's last %d "
                  "successful job%s, plus writing %lld frames and the histories; time in the "
                  "queue not included",
                  speed, used, used == 1 ? "" : "s", static_cast<long long>(estimate.frames));
  } else if (calibrated) {
    std::snprintf(note, sizeof note,
                  "estimate: %.3g particle-steps per second, this server's own speed on the "
                  "seed paper's case (%.0f particles, %.0f steps in %.2f s, measured at its first "
                  "preview), plus writing %lld frames and the histories; time in the queue not "
                  "included",
                  speed, calibration.particles, calibration.steps, calibration.wall_s,
                  static_cast<long long>(estimate.frames));
  } else {
    std::snprintf(note, sizeof note,
                  "estimate: %.3g particle-steps per second, a figure measured on a 2-core "
                  "machine (this server has no finished job of 1 s or more to measure yet), "
                  "plus writing %lld frames and the histories",
                  speed, static_cast<long long>(estimate.frames));
  }
  e["note"] = note;
  if (fe) {
    e["fe_check_basis"] = fe->basis;
    char more[200];
    if (fe->basis == "measured") {
      std::snprintf(more, sizeof more,
                    "; plus the FE check: %.0f s, the mean of this server's last %d checks",
                    fe->seconds, fe->checks_measured);
    } else {
      std::snprintf(more, sizeof more,
                    "; plus the FE check: %.0f s, measured on a 2-core machine (this server "
                    "has run none yet)",
                    fe->seconds);
    }
    e["note"] = std::string(note) + more;
  }
  return e;
}

nlohmann::json describe(const PreparedJob& job, const JobEstimate& estimate) {
  const Simulation& sim = job.scene.sim;
  const Particles& p = sim.particles;
  nlohmann::json bodies = nlohmann::json::array();
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (std::size_t i = 0; i < p.n; ++i) {
    x0 = std::min(x0, p.x[i]);
    x1 = std::max(x1, p.x[i]);
    y0 = std::min(y0, p.y[i]);
    y1 = std::max(y1, p.y[i]);
  }
  for (const Body& b : sim.bodies) {
    std::size_t driven = 0;
    for (std::size_t i = b.begin; i < b.end; ++i) driven += p.motion[i] != 0;
    bodies.push_back({{"name", b.name},
                      {"particles", b.count()},
                      {"free", b.count() - driven},
                      {"driven", driven},
                      {"E_Pa", b.material.E},
                      {"nu", b.material.nu},
                      {"rho_kg_m3", b.material.rho0}});
  }
  nlohmann::json outlines = nlohmann::json::array();
  for (const Outline& o : job.scene.outlines) {
    nlohmann::json points = nlohmann::json::array();
    for (const auto& q : o.points) {
      // To 0.1 um: far below any spacing, and it keeps the answer small.
      points.push_back({rounded(q[0], 1e-7), rounded(q[1], 1e-7)});
      x0 = std::min(x0, q[0]);
      x1 = std::max(x1, q[0]);
      y0 = std::min(y0, q[1]);
      y1 = std::max(y1, q[1]);
    }
    const bool has_body = o.body >= 0 && static_cast<std::size_t>(o.body) < sim.bodies.size();
    outlines.push_back({{"name", o.name},
                        {"body", has_body ? nlohmann::json(sim.bodies[o.body].name) : nullptr},
                        {"closed", o.closed},
                        {"points", std::move(points)}});
  }
  nlohmann::json out = {
      {"scene", job.scene.type},
      {"name", job.job.at("name")},
      {"particles", estimate.particles},
      {"bodies", std::move(bodies)},
      {"spacing_m", sim.discretization.dx},
      {"finest_spacing_m", p.spacing.empty()
                               ? sim.discretization.dx
                               : *std::min_element(p.spacing.begin(), p.spacing.end())},
      {"dt_s", job.time_step.dt},
      {"dt_limit_s", job.time_step.dt_limit},
      {"end_s", job.end_s},
      {"steps", estimate.steps},
      {"frames", estimate.frames},
      {"particle_steps", estimate.particle_steps},
      {"disk_bytes", estimate.disk_bytes},
      {"bounds_m", {x0, y0, x1, y1}},
      {"outlines", std::move(outlines)},
      {"model", job.scene.description},
      {"built", true},
      {"job", job.job},
  };
  if (p.n <= kMaxListedParticles) {
    nlohmann::json x = nlohmann::json::array(), y = nlohmann::json::array();
    nlohmann::json body = nlohmann::json::array(), driven = nlohmann::json::array();
    for (std::size_t i = 0; i < p.n; ++i) {
      x.push_back(rounded(p.x[i], 1e-7));
      y.push_back(rounded(p.y[i], 1e-7));
      body.push_back(p.body[i]);
      driven.push_back(p.motion[i] != 0 ? 1 : 0);
    }
    out["points"] = {{"x", std::move(x)},
                     {"y", std::move(y)},
                     {"body", std::move(body)},
                     {"driven", std::move(driven)}};
  } else {
    out["points"] = nullptr;
    out["points_omitted"] =
        "more than " + std::to_string(kMaxListedParticles) + " particles: outlines only";
  }
  return out;
}

// A job beyond the build budget: its size from the solver's estimate,
// without bodies, outlines or particles.
nlohmann::json describe_estimate(const nlohmann::json& job, const JobSize& size,
                                 const JobEstimate& estimate, const Limits& limits) {
  const nlohmann::json& d = job.at("discretization");
  return {
      {"scene", job.at("scene").at("type")},
      {"name", job.at("name")},
      {"built", false},
      {"particles", estimate.particles},
      {"steps", estimate.steps},
      {"frames", estimate.frames},
      {"particle_steps", estimate.particle_steps},
      {"disk_bytes", estimate.disk_bytes},
      {"end_s", size.end_s},
      {"spacing_m", d.contains("spacing_m")    ? d.at("spacing_m").get<double>()
                    : d.contains("spacing_mm") ? 1e-3 * d.at("spacing_mm").get<double>()
                                               : 0.0},
      {"estimate", size.to_json()},
      {"build_budget_particles", limits.max_built_particles},
      {"points", nullptr},
      {"points_omitted", "about " + std::to_string(estimate.particles) +
                             std::string(size.body_fitted ? " body-fitted" : "") +
                             " particles, more than this server builds for a preview "
                             "(--build-budget): counts estimated from coarser copies of the "
                             "job, no geometry"},
      {"job", job},
  };
}

// The preview of a valid job, before the run-time estimate: built within
// the build budget, else estimated.
std::pair<nlohmann::json, JobEstimate> preview_of(const nlohmann::json& job, const Limits& limits) {
  const JobSize size = estimate_job_size(job);
  const JobEstimate estimated = estimate_job(job, size);
  const bool build = within_build_budget(size, limits) && over_limits(estimated, limits).empty();
  std::shared_ptr<const PreparedJob> prepared = size.built;
  if (build && !prepared) prepared = std::make_shared<const PreparedJob>(prepare_job(job, 1));
  const JobEstimate estimate = prepared ? estimate_job(*prepared) : estimated;
  nlohmann::json doc =
      prepared ? describe(*prepared, estimate) : describe_estimate(job, size, estimated, limits);
  // A preview of a job this server would refuse still shows what it can,
  // and says why it would be refused, at the fields concerned.
  doc["accepted"] = true;
  doc["valid"] = true;
  doc["errors"] = nlohmann::json::array();
  if (auto over = over_limits(estimate, limits); !over.empty()) {
    doc["accepted"] = false;
    doc["errors"] = problem::errors(over);
    doc["limits"] = limits_json(limits);
  }
  return {std::move(doc), estimate};
}

nlohmann::json refused(const std::string& pointer, const std::string& message) {
  return {{"accepted", false}, {"valid", true}, {"errors", problem::errors({{pointer, message}})}};
}

}  // namespace

Response preview(Services& s, Request& req) {
  auto body = read_json_body(req);
  if (auto* refusal = std::get_if<StringResponse>(&body)) return std::move(*refusal);
  const nlohmann::json& raw = std::get<nlohmann::json>(body);
  const Limits& limits = s.config.limits;
  try {
    const nlohmann::json job = validate_job(raw);
    // What POST /jobs refuses with 501 is no preview either.
    if (auto fe = fe_refusal(s, job)) {
      return json_response(http::status::ok, refused(fe->issues[0].pointer, fe->issues[0].message));
    }
    const std::string key = job.dump();
    std::optional<nlohmann::json> doc = s.previews.find(key);
    const bool cached = doc.has_value();
    if (!doc) {
      const SetupStop stop(std::chrono::steady_clock::now() + s.config.timeouts.build, req.gone);
      auto [built, estimate] = preview_of(job, limits);
      built["run_time_basis"] = {{"particle_steps", estimate.particle_steps},
                                 {"output_s", estimate.output_s},
                                 {"frames", estimate.frames}};
      s.previews.put(key, built);
      doc = std::move(built);
    }
    // The run time from this server's speed now, not when the answer was kept.
    JobEstimate e;
    e.particle_steps = doc->at("run_time_basis").at("particle_steps").get<double>();
    e.output_s = doc->at("run_time_basis").at("output_s").get<double>();
    e.frames = doc->at("run_time_basis").at("frames").get<std::int64_t>();
    doc->erase("run_time_basis");
    (*doc)["run_time"] = run_time_estimate(s, e, runs_fe_check(job));
    (*doc)["cached"] = cached;
    return json_response(http::status::ok, *doc);
  } catch (const InvalidJob& e) {
    // The preview of an invalid job is its list of problems: a page checking
    // a form as it is typed gets an answer, not an error, for each keystroke.
    return json_response(http::status::ok, {{"accepted", false},
                                            {"valid", false},
                                            {"title", "Invalid job"},
                                            {"type", problem::kInvalidJob},
                                            {"errors", problem::errors(e.issues)}});
  } catch (const SetupStopped& e) {
    log_line(LogLevel::info, "gearsph serve: POST /preview: stopped: %s\n", e.what());
    return json_response(
        http::status::ok,
        refused("/discretization", std::string(e.what()) + ": the scene is too large to preview "
                                                           "within this server's build timeout"));
  }
}

}  // namespace gearsph::server::routes
