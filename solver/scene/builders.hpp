#pragma once
// Scene builders, one per scene type. Each takes the job's `scene` object
// (validated, defaults applied) and the discretisation, whose spacing may be
// left open (0) for the scene to choose its default.
#include <functional>

#include <nlohmann/json.hpp>

#include "solver/geometry/region.hpp"
#include "solver/geometry/spacing_field.hpp"
#include "solver/scene/scene.hpp"

namespace gearsph::scenes {

// The discretisation as the job gives it; dx = 0 when the job leaves it open.
struct SceneInput {
  const nlohmann::json& scene;
  Discretization discretization;
  double end_s = 0.0;  // the job's end time, 0 when it takes the scene's default
};

Material read_material(const nlohmann::json& material);

Scene build_plate(const SceneInput& in);            // validation.md section 5
Scene build_strip_wave(const SceneInput& in);       // validation.md section 2
Scene build_spinning_disk(const SceneInput& in);    // validation.md section 4
Scene build_bar_impact(const SceneInput& in);       // validation.md section 3
Scene build_hertz(const SceneInput& in);            // validation.md section 6
Scene build_rack_pinion(const SceneInput& in);      // the seed paper's gear case
Scene build_tension_strip(const SceneInput& in);    // stability study: tensile instability
Scene build_plate_with_hole(const SceneInput& in);  // validation.md section 10: Kirsch
Scene build_thick_cylinder(const SceneInput& in);   // validation.md section 10: Lame
Scene build_cracked_plate(const SceneInput& in);    // docs/cracks.md: K_I, K_II against Tada

// Common helpers for builders.

// Every builder's opening: a scene of `type` on the job's discretisation,
// whose spacing the builder then fixes (lattice_scene_spacings,
// graded_scene_spacings).
Scene start_scene(const std::string& type, const SceneInput& in);

void add_body(Simulation& sim, const std::string& name, const Material& material);
// Adds one particle to the last body (mass rho0 dx^2 per unit thickness, or
// rho0 * volume when a volume is given; spacing dx, or the one given).
std::size_t add_particle(Simulation& sim, double x, double y, int motion, double volume = 0.0,
                         double spacing = 0.0);
// Closes the last body's particle range.
void end_body(Simulation& sim);
// Domain: the particles' bounding box grown by `margin` on every side.
Box grown_bounds(const Particles& p, double margin);

// The layout a scene uses: the job's, or `scene_default`. Scenes that cannot
// place body-fitted particles pass `fitted_ok` false and get a JobError.
ParticleLayout particle_layout(const Discretization& d, ParticleLayout scene_default,
                               bool fitted_ok = true);
struct SceneSpacings {
  bool fitted = false;
  double dx = 0.0;       // lattice spacing, or the body-fitted bulk spacing
  double fine = 0.0;     // body-fitted: at the scene's stress raiser (dx: uniform)
  double grading = 0.0;  // body-fitted: the job's growth of the spacing, or the default
};
// The spacings of a scene on a lattice by default whose body-fitted
// particles are graded only when the job gives a fine spacing (plate,
// strip, disk, bars): sets d.dx to `default_dx` when the job leaves it open,
// and refuses a fine spacing above the bulk one.
SceneSpacings lattice_scene_spacings(Discretization& d, double default_dx);
// The spacings of a scene whose body-fitted particles are graded by default
// (gears, plate with a hole, thick cylinder): sets d.dx to `default_dx` when
// the job leaves it open; body-fitted, the fine spacing is the job's or
// `default_fine` (at most the bulk one). Checks nothing: the builder calls
// require_fine_within_bulk after its own checks of the bulk spacing.
SceneSpacings graded_scene_spacings(Discretization& d, bool fitted, double default_dx,
                                    double default_fine);
// Refuses a fine spacing above the bulk one.
void require_fine_within_bulk(const SceneSpacings& spacings);
// The layout and spacings in a scene's description (its summary's "model").
void describe_spacings(nlohmann::json& description, const SceneSpacings& spacings);
const char* layout_name(bool fitted);  // "body_fitted" or "lattice"

// A polygon drawn as the outline of `body`.
Outline polygon_outline(const std::string& name, int body, const geometry::Polygon& polygon);

// Dynamic relaxation to the static state (Hertz, Kirsch, Lame, a gear's
// static check): mass-proportional damping at the angular frequency of the
// slowest mode the load excites (damping ratio 1/2 for that mode, heavier
// for slower ones), the load ramped up over ten of its periods, and by
// default held as long again.
void relax_to_static(Scene& scene, double omega_slowest);

// While one is in scope on this thread, body-fitted fills (add_body_fitted)
// place their seeded particles without relaxing them: as many particles, in
// a fraction of the time, for a job's sizing (solver/job/job_size.hpp).
class CountOnlyScope {
 public:
  CountOnlyScope();
  ~CountOnlyScope();
  CountOnlyScope(const CountOnlyScope&) = delete;
  CountOnlyScope& operator=(const CountOnlyScope&) = delete;
};

// Fills `region` with body-fitted particles graded by `spacing` and adds
// them to the last body (volume: the clipped Voronoi cell), marking the body
// fitted; motion_of(x, y) gives each particle's motion index. Returns the
// relaxation's iterations.
int add_body_fitted(Simulation& sim, const geometry::Region& region,
                    const geometry::SpacingField& spacing,
                    const std::function<int(double, double)>& motion_of);

}  // namespace gearsph::scenes
