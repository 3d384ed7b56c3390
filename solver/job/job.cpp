#include "solver/job/job.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "solver/core/json_schema.hpp"
#include "solver/core/passes.hpp"
#include "solver/gear/iso6336_error.hpp"
#include "solver/gear/iso6336_materials.hpp"
#include "solver/integrate/integrator.hpp"
#include "solver/physics/contact.hpp"
#include "solver/scene/builders.hpp"
#include "solver/scene/surfaces.hpp"

namespace gearsph {

extern const char* const kJobSchemaText;

namespace {

std::string summarise(const std::vector<JobIssue>& issues) {
  std::ostringstream s;
  s << "invalid job:";
  for (const JobIssue& i : issues)
    s << "\n  " << (i.pointer.empty() ? "/" : i.pointer) << ": " << i.message;
  return s.str();
}

[[noreturn]] void refuse(const std::string& pointer, const std::string& message) {
  throw InvalidJob({{pointer, message}});
}

const jsonschema::Validator& validator() {
  static const jsonschema::Validator v(job_schema());
  return v;
}

// Default smoothing length: every kernel reaches 3 dx (method.md: kappa = 1
// for the seed paper's support-3h kernel).
double default_h_over_dx(KernelType k) {
  return kernel_support(k) >= 3.0 ? 1.0 : 1.5;
}

Discretization read_discretization(const nlohmann::json& d) {
  Discretization out;
  out.kernel = *kernel_from_name(d.at("kernel").get<std::string>());
  if (d.contains("spacing_m") && d.contains("spacing_mm")) {
    refuse("/discretization/spacing_mm",
           "give the spacing once: spacing_m or spacing_mm, not both");
  }
  out.dx = d.contains("spacing_m")    ? d.at("spacing_m").get<double>()
           : d.contains("spacing_mm") ? 1e-3 * d.at("spacing_mm").get<double>()
                                      : 0.0;
  out.h_over_dx =
      d.contains("h_over_dx") ? d.at("h_over_dx").get<double>() : default_h_over_dx(out.kernel);
  if (d.contains("particles")) {
    out.layout = d.at("particles").get<std::string>() == "lattice" ? ParticleLayout::Lattice
                                                                   : ParticleLayout::BodyFitted;
  }
  if (d.contains("fine_spacing_m") && d.contains("fine_spacing_mm")) {
    refuse("/discretization/fine_spacing_mm",
           "give the fine spacing once: fine_spacing_m or fine_spacing_mm, not both");
  }
  out.fine_dx = d.contains("fine_spacing_m")    ? d.at("fine_spacing_m").get<double>()
                : d.contains("fine_spacing_mm") ? 1e-3 * d.at("fine_spacing_mm").get<double>()
                                                : 0.0;
  if (d.contains("grading")) out.grading = d.at("grading").get<double>();
  if (d.contains("contact_spacing_m") && d.contains("contact_spacing_mm")) {
    refuse("/discretization/contact_spacing_mm",
           "give the contact spacing once: contact_spacing_m or contact_spacing_mm, not both");
  }
  out.contact_dx = d.contains("contact_spacing_m") ? d.at("contact_spacing_m").get<double>()
                   : d.contains("contact_spacing_mm")
                       ? 1e-3 * d.at("contact_spacing_mm").get<double>()
                       : 0.0;
  if (out.layout == ParticleLayout::Lattice && out.contact_dx > 0.0) {
    refuse(d.contains("contact_spacing_m") ? "/discretization/contact_spacing_m"
                                           : "/discretization/contact_spacing_mm",
           "a lattice has one spacing: a contact spacing needs \"particles\": \"body_fitted\"");
  }
  if (out.layout == ParticleLayout::Lattice && (out.fine_dx > 0.0 || d.contains("grading"))) {
    refuse(d.contains("grading")          ? "/discretization/grading"
           : d.contains("fine_spacing_m") ? "/discretization/fine_spacing_m"
                                          : "/discretization/fine_spacing_mm",
           "a lattice has one spacing: grading needs \"particles\": \"body_fitted\"");
  }
  return out;
}

ContactConfig read_contact(const nlohmann::json& c) {
  ContactConfig out;
  const std::string model = c.at("model").get<std::string>();
  out.model = model == "kernel"            ? ContactModel::Kernel
              : model == "hertz"           ? ContactModel::Hertz
              : model == "surface_penalty" ? ContactModel::Surface
                                           : ContactModel::SeedPenalty;
  out.D = c.at("D").get<double>();
  out.damping_ratio = c.at("damping_ratio").get<double>();
  out.r0_over_dx = c.at("r0_over_dx").get<double>();
  out.near_field = c.at("hertz_near_field").get<bool>();
  if (c.contains("smoothing_spacings")) {
    out.smoothing_spacings = c.at("smoothing_spacings").get<double>();
  } else {
    out.smoothing_spacings = -1.0;  // the scene's (prepare_job)
  }
  return out;
}

MethodConfig read_method(const nlohmann::json& m) {
  MethodConfig out;
  out.formulation = m.at("formulation").get<std::string>() == "total_lagrangian"
                        ? Formulation::TotalLagrangian
                        : Formulation::UpdatedLagrangian;
  const std::string corr = m.at("gradient_correction").get<std::string>();
  out.correction = corr == "none"     ? GradientCorrection::None
                   : corr == "linear" ? GradientCorrection::Linear
                                      : GradientCorrection::Quadratic;
  const auto& av = m.at("artificial_viscosity");
  out.viscosity.alpha = av.at("alpha").get<double>();
  out.viscosity.beta = av.at("beta").get<double>();
  out.viscosity.eta_over_h = av.at("eta_over_h").get<double>();
  const auto& as = m.at("artificial_stress");
  out.artificial_stress.epsilon = as.at("epsilon").get<double>();
  out.artificial_stress.n = as.at("n").get<int>();
  // The total-Lagrangian kernel never sees the deformed spacing: no tensile
  // instability, so artificial stress does not apply there.
  if (out.formulation == Formulation::TotalLagrangian) out.artificial_stress.epsilon = 0.0;
  out.hourglass.coefficient = m.at("hourglass").at("coefficient").get<double>();
  return out;
}

// The FE check (fe/fe_check.hpp) compares static fillet stresses: it needs
// a quasi-static run that carries a load. Refused here, before a run, so
// that the CLI and the service answer alike.
void check_fe_request(const nlohmann::json& job) {
  if (!job.contains("scene") || !job["scene"].is_object()) return;
  const nlohmann::json& s = job["scene"];
  if (s.value("type", "") != "rack_pinion" || !s.value("fe_check", false)) return;
  if (!s.value("quasi_static", false)) {
    refuse("/scene/fe_check",
           "the FE check compares static stresses: it needs \"quasi_static\": true");
  }
  if (!(s.contains("rack") && s["rack"].value("load_N", 0.0) > 0.0)) {
    refuse("/scene/rack/load_N", "the FE check needs a load: give the rack load per gear");
  }
}

// Materials with strength (ISO 6336-5 class, limits, yield) are resolved
// here, so that a class without a built-in line or a hardness off its line
// is refused before a run, at its field, like any other bad value.
void check_material_strength(const nlohmann::json& node, const std::string& pointer,
                             std::vector<JobIssue>& issues) {
  if (node.is_array()) {
    for (std::size_t k = 0; k < node.size(); ++k) {
      check_material_strength(node[k], pointer + "/" + std::to_string(k), issues);
    }
    return;
  }
  if (!node.is_object()) return;
  if (node.contains("E_Pa") && gear::iso6336::has_strength(node)) {
    try {
      gear::iso6336::read_gear_material(node, pointer);
    } catch (const gear::iso6336::InvalidRating& e) {
      for (const auto& i : e.issues) issues.push_back({i.pointer, i.message});
    }
    return;
  }
  for (auto it = node.begin(); it != node.end(); ++it) {
    check_material_strength(*it, pointer + "/" + jsonschema::escape_pointer_token(it.key()),
                            issues);
  }
}

Scene build_scene(const nlohmann::json& job, const Discretization& disc) {
  const nlohmann::json& s = job.at("scene");
  const std::string type = s.at("type").get<std::string>();
  const nlohmann::json& t = job.at("time");
  const scenes::SceneInput in{s, disc, t.contains("end_s") ? t.at("end_s").get<double>() : 0.0};
  if (type == "plate") return scenes::build_plate(in);
  if (type == "strip_wave") return scenes::build_strip_wave(in);
  if (type == "spinning_disk") return scenes::build_spinning_disk(in);
  if (type == "bar_impact") return scenes::build_bar_impact(in);
  if (type == "hertz") return scenes::build_hertz(in);
  if (type == "rack_pinion") return scenes::build_rack_pinion(in);
  if (type == "tension_strip") return scenes::build_tension_strip(in);
  if (type == "plate_with_hole") return scenes::build_plate_with_hole(in);
  if (type == "thick_cylinder") return scenes::build_thick_cylinder(in);
  if (type == "cracked_plate") return scenes::build_cracked_plate(in);
  refuse("/scene/type", "is not a scene this build knows");
}

}  // namespace

InvalidJob::InvalidJob(std::vector<JobIssue> list)
    : std::runtime_error(summarise(list)), issues(std::move(list)) {}

const nlohmann::json& job_schema() {
  static const nlohmann::json schema = nlohmann::json::parse(kJobSchemaText);
  return schema;
}

nlohmann::json parse_job_text(const std::string& text) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    std::string what = e.what();
    // nlohmann prefixes "[json.exception.parse_error.101] "; keep the sentence.
    const auto cut = what.find("] ");
    if (cut != std::string::npos) what = what.substr(cut + 2);
    refuse("", "is not valid JSON: " + what);
  }
}

nlohmann::json validate_job(const nlohmann::json& job) {
  const std::vector<jsonschema::Error> errors = validator().validate(job);
  if (!errors.empty()) {
    std::vector<JobIssue> issues;
    for (const auto& e : errors) issues.push_back({e.pointer, e.message});
    throw InvalidJob(std::move(issues));
  }
  if (job.contains("time") && job["time"].is_object() && job["time"].contains("dt_s") &&
      job["time"].contains("cfl")) {
    refuse("/time/cfl", "give either dt_s (a fixed step) or cfl, not both");
  }
  nlohmann::json full = validator().apply_defaults(job);
  check_fe_request(full);
  std::vector<JobIssue> strength;
  if (full.contains("scene")) check_material_strength(full["scene"], "/scene", strength);
  if (!strength.empty()) throw InvalidJob(std::move(strength));
  return full;
}

int threads_for(std::size_t particles, int max_threads) {
  const std::size_t worth = std::max<std::size_t>(1, particles / kParticlesPerThread);
  return static_cast<int>(
      std::min<std::size_t>(worth, static_cast<std::size_t>(std::max(1, max_threads))));
}

PreparedJob prepare_job(const nlohmann::json& raw, int threads, int max_threads) {
  PreparedJob out;
  out.job = validate_job(raw);
  const nlohmann::json& job = out.job;
  try {
    const Discretization disc = read_discretization(job.at("discretization"));
    out.scene = build_scene(job, disc);
  } catch (const JobError& e) {
    refuse(e.pointer, e.what());
  }
  Simulation& sim = out.scene.sim;
  sim.method = read_method(job.at("method"));
  const auto [finest, coarsest] =
      std::minmax_element(sim.particles.spacing.begin(), sim.particles.spacing.end());
  if (sim.method.formulation == Formulation::UpdatedLagrangian && sim.particles.n > 0 &&
      *finest != *coarsest) {
    refuse("/method/formulation",
           "graded particles (a fine spacing below the bulk one) need the total-Lagrangian form: "
           "the updated-Lagrangian step has one smoothing length; set "
           "/method/formulation to \"total_lagrangian\" or give no fine spacing");
  }
  if (!sim.cracks.empty() && sim.method.formulation == Formulation::UpdatedLagrangian) {
    refuse("/method/formulation",
           "a crack is a cut in the reference neighbourhoods, which only the total-Lagrangian "
           "form keeps: set /method/formulation to \"total_lagrangian\"");
  }
  // A total-Lagrangian run never takes an updated-Lagrangian step: free
  // those 29 arrays now rather than at integrate::initialise, before the
  // stable-step estimate below builds the reference pairs beside them (the
  // set-up's peak of memory; docs/speed-accuracy-history.md).
  if (sim.method.formulation == Formulation::TotalLagrangian) {
    sim.particles.release_updated_lagrangian();
  }
  if (sim.bodies.size() > 1) scenes::assign_surfaces(out.scene);
  sim.contact = read_contact(job.at("method").at("contact"));
  if (sim.contact.smoothing_spacings < 0.0) {
    sim.contact.smoothing_spacings = out.scene.contact_smoothing_spacings;
  }
  if (sim.contact.model == ContactModel::Kernel &&
      sim.method.formulation == Formulation::TotalLagrangian) {
    refuse("/method/contact/model",
           "kernel coupling between bodies needs the updated-Lagrangian formulation (the "
           "total-Lagrangian kernel lives on each body's reference configuration); set "
           "/method/formulation to \"updated_lagrangian\"");
  }
  const int job_threads = job.at("threads").get<int>();
  const int most = max_threads > 0 ? max_threads : available_threads();
  sim.threads = threads > 0 ? threads : job_threads > 0 ? std::min(job_threads, most) : 1;
  out.threads_by = threads > 0 ? "caller" : job_threads > 0 ? "job" : "size";
  // A scene big enough to take its threads by size without a trial
  // (choose_threads, below) has them for its set-up too: the stable-step
  // estimate gives the same step on any number of threads.
  if (out.threads_by == "size" && sim.particles.n >= kThreadsWithoutTrial) {
    sim.threads = threads_for(sim.particles.n, most);
  }

  const nlohmann::json& t = job.at("time");
  out.end_s = t.contains("end_s") ? t.at("end_s").get<double>() : out.scene.default_end_s;
  TimeStepRequest request;
  if (t.contains("dt_s")) request.dt_s = t.at("dt_s").get<double>();
  if (t.contains("cfl")) request.cfl = t.at("cfl").get<double>();
  // A scene may carry its own default step (the seed paper's case: 4e-8 s).
  request.allow_unstable = t.at("allow_unstable").get<bool>();
  request.extra_limit_s = physics::contact_time_step_limit(sim);
  request.extra_name = "contact stiffness";
  // A scene may carry its own default step (the seed paper's case: 4e-8 s at
  // 1 mm); at a finer spacing it may be unstable, and then the automatic
  // step applies instead.
  bool scene_step = false;
  if (!request.dt_s && !request.cfl && out.scene.default_dt_s > 0) {
    request.dt_s = out.scene.default_dt_s;
    scene_step = true;
  }
  try {
    out.time_step = choose_time_step(sim, request);
    if (scene_step) out.time_step.chosen_by = "scene default";
  } catch (const TimeStepError& e) {
    if (!scene_step) refuse(request.dt_s ? "/time/dt_s" : "/time/cfl", e.what());
    request.dt_s.reset();
    out.time_step = choose_time_step(sim, request);
  }
  sim.dt = out.time_step.dt;
  out.steps = static_cast<std::int64_t>(std::ceil(out.end_s / sim.dt - 1e-9));
  constexpr std::int64_t kMaxSteps = 2'000'000'000;
  if (out.steps > kMaxSteps) {
    refuse("/time/end_s", "asks for " + std::to_string(out.steps) + " time steps; at most " +
                              std::to_string(kMaxSteps) + " are allowed");
  }
  // Rounded up, so that a run records at most the samples and frames asked
  // for (plus the initial state): 1.9x as many steps as points would
  // otherwise sample every step, 1.9x the rows.
  auto every = [&](std::int64_t wanted) {
    return std::max<std::int64_t>(1, (out.steps + wanted - 1) / wanted);
  };
  const nlohmann::json& output = job.at("output");
  if (output.contains("history_points")) {
    out.history_every = every(output.at("history_points").get<std::int64_t>());
  } else if (out.scene.history_every_step) {
    out.history_every = every(kDefaultHistoryPoints);
  } else {
    // By time, not by step: kDefaultHistoryPoints over the run, but not
    // closer than kDefaultHistoryMinSteps steps, so that a short run does not
    // spend a sixth of its time on a row every step (docs/speed-accuracy-history.md,
    // "Outputs"). The run's own checks keep their cadence (runner.cpp).
    out.history_every = std::max(every(kDefaultHistoryPoints), kDefaultHistoryMinSteps);
  }
  const auto frames = job.at("output").at("frames").get<std::int64_t>();
  out.compress_frames = job.at("output").at("compress").get<bool>();
  if (frames > 0) {
    out.snapshot_every = every(frames);
    out.frames = 1 + out.steps / out.snapshot_every + (out.steps % out.snapshot_every ? 1 : 0);
  }
  if (out.threads_by == "size") choose_threads(out, most);
  return out;
}

void choose_threads(PreparedJob& job, int max_threads) {
  Simulation& sim = job.scene.sim;
  const std::size_t n = sim.particles.n;
  const int worth = threads_for(n, max_threads);
  job.threads_by = "size";
  job.trial_threads = 0;
  sim.threads = 1;
  if (n >= kThreadsWithoutTrial) {
    sim.threads = worth;
  } else if (worth > 1 && double(n) * double(job.steps) >= kTrialParticleSteps) {
    job.threads_by = "trial";
    job.trial_threads = worth;
  }
}

}  // namespace gearsph
