// What every scene builder shares (builders.hpp): its opening, bodies and
// particles, spacings, outlines and the static relaxation.
#include <algorithm>
#include <numbers>

#include "solver/core/setup_progress.hpp"
#include "solver/geometry/body_fitted.hpp"
#include "solver/scene/builders.hpp"

namespace gearsph::scenes {

Material read_material(const nlohmann::json& m) {
  Material mat;
  mat.E = m.at("E_Pa").get<double>();
  mat.nu = m.at("nu").get<double>();
  mat.rho0 = m.at("rho_kg_m3").get<double>();
  return mat;
}

Scene start_scene(const std::string& type, const SceneInput& in) {
  Scene scene;
  scene.type = type;
  scene.sim.discretization = in.discretization;
  return scene;
}

void add_body(Simulation& sim, const std::string& name, const Material& material) {
  Body b;
  b.name = name;
  b.material = material;
  b.begin = b.end = sim.particles.n;
  sim.bodies.push_back(b);
}

std::size_t add_particle(Simulation& sim, double x, double y, int motion, double volume,
                         double spacing) {
  const Material& mat = sim.bodies.back().material;
  const double dx = sim.discretization.dx;
  const std::size_t i = sim.particles.n;
  // A large lattice is filled without another set-up stage: a stop in
  // scope (SetupStop) is heard here too.
  if ((i & 4095) == 0) setup_progress("placing particles", 0.0);
  const double v = volume > 0.0 ? volume : dx * dx;
  sim.particles.add(x, y, mat.rho0 * v, mat.rho0, static_cast<int>(sim.bodies.size() - 1), motion,
                    spacing > 0.0 ? spacing : dx);
  sim.particles.cs[i] = mat.p_wave_speed();
  return i;
}

void end_body(Simulation& sim) {
  sim.bodies.back().end = sim.particles.n;
}

Box grown_bounds(const Particles& p, double margin) {
  Box b{p.x[0], p.y[0], p.x[0], p.y[0]};
  for (std::size_t i = 0; i < p.n; ++i) {
    b.x_min = std::min(b.x_min, p.x[i]);
    b.x_max = std::max(b.x_max, p.x[i]);
    b.y_min = std::min(b.y_min, p.y[i]);
    b.y_max = std::max(b.y_max, p.y[i]);
  }
  b.x_min -= margin;
  b.y_min -= margin;
  b.x_max += margin;
  b.y_max += margin;
  return b;
}

ParticleLayout particle_layout(const Discretization& d, ParticleLayout scene_default,
                               bool fitted_ok) {
  const ParticleLayout l = d.layout == ParticleLayout::SceneDefault ? scene_default : d.layout;
  if (l == ParticleLayout::BodyFitted && !fitted_ok) {
    throw JobError("/discretization/particles",
                   "this scene places its particles on a lattice only (its grips are "
                   "lattice rows)");
  }
  if (l == ParticleLayout::Lattice && (d.fine_dx > 0.0 || d.grading > 0.0)) {
    throw JobError("/discretization/particles",
                   "a lattice has one spacing: a fine spacing or a grading needs "
                   "\"particles\": \"body_fitted\"");
  }
  return l;
}

SceneSpacings lattice_scene_spacings(Discretization& d, double default_dx) {
  SceneSpacings out;
  out.fitted = particle_layout(d, ParticleLayout::Lattice) == ParticleLayout::BodyFitted;
  if (d.dx <= 0) d.dx = default_dx;
  out.dx = d.dx;
  out.fine = out.fitted && d.fine_dx > 0 ? d.fine_dx : out.dx;
  out.grading = d.grading > 0 ? d.grading : geometry::kDefaultGrading;
  require_fine_within_bulk(out);
  return out;
}

SceneSpacings graded_scene_spacings(Discretization& d, bool fitted, double default_dx,
                                    double default_fine) {
  SceneSpacings out;
  out.fitted = fitted;
  if (d.dx <= 0) d.dx = default_dx;
  out.dx = d.dx;
  out.fine = fitted ? (d.fine_dx > 0 ? d.fine_dx : std::min(d.dx, default_fine)) : d.dx;
  out.grading = d.grading > 0 ? d.grading : geometry::kDefaultGrading;
  return out;
}

void require_fine_within_bulk(const SceneSpacings& spacings) {
  if (spacings.fine > spacings.dx) {
    throw JobError("/discretization/fine_spacing_m",
                   "the fine spacing must not exceed the bulk spacing");
  }
}

const char* layout_name(bool fitted) {
  return fitted ? "body_fitted" : "lattice";
}

void describe_spacings(nlohmann::json& description, const SceneSpacings& spacings) {
  description["particles"] = layout_name(spacings.fitted);
  description["fine_spacing_m"] = spacings.fine;
  description["bulk_spacing_m"] = spacings.dx;
}

Outline polygon_outline(const std::string& name, int body, const geometry::Polygon& polygon) {
  Outline o;
  o.name = name;
  o.body = body;
  for (const geometry::Point& q : polygon) o.points.push_back({q.x, q.y});
  return o;
}

void relax_to_static(Scene& scene, double omega_slowest) {
  Simulation& sim = scene.sim;
  sim.damping_1_s = omega_slowest;
  sim.load_ramp_s = 10.0 * 2.0 * std::numbers::pi / omega_slowest;
  scene.default_end_s = 2.0 * sim.load_ramp_s;
}

namespace {

thread_local int count_only_scopes = 0;
// A few relaxation sweeps even so: the seeds' closest pairs would set a
// stable step well below the relaxed particles' (1.7 against 0.96 million
// steps for rack_pinion at 0.5 mm unrelaxed, 0.97 after 8 sweeps).
constexpr int kCountOnlyIterations = 6;

}  // namespace

CountOnlyScope::CountOnlyScope() {
  ++count_only_scopes;
}

CountOnlyScope::~CountOnlyScope() {
  --count_only_scopes;
}

int add_body_fitted(Simulation& sim, const geometry::Region& region,
                    const geometry::SpacingField& spacing,
                    const std::function<int(double, double)>& motion_of) {
  geometry::BodyFittedOptions options;
  // The relaxation moves the seeded particles, never adds or removes one;
  // it is most of a body-fitted set-up (4 s of 4.2 for 1,190 particles).
  if (count_only_scopes > 0) options.max_iterations = kCountOnlyIterations;
  const geometry::BodyFittedParticles b = geometry::fill_body_fitted(region, spacing, options);
  for (std::size_t i = 0; i < b.points.size(); ++i) {
    const geometry::Point q = b.points[i];
    add_particle(sim, q.x, q.y, motion_of(q.x, q.y), b.volume[i], b.spacing[i]);
  }
  sim.bodies.back().fitted = true;
  return b.iterations;
}

}  // namespace gearsph::scenes
