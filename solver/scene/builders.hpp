#pragma once
// Scene builders, one per scene type. Each takes the job's `scene` object
// (validated, defaults applied) and the discretisation, whose spacing may be
// left open (0) for the scene to choose its default.
#include <nlohmann/json.hpp>

#include "solver/scene/scene.hpp"

namespace gearsph::scenes {

// The discretisation as the job gives it; dx = 0 when the job leaves it open.
struct SceneInput {
  const nlohmann::json& scene;
  Discretization discretization;
  double end_s = 0.0;  // the job's end time, 0 when it takes the scene's default
};

Material read_material(const nlohmann::json& material);

Scene build_plate(const SceneInput& in);          // validation.md section 5
Scene build_strip_wave(const SceneInput& in);     // validation.md section 2
Scene build_spinning_disk(const SceneInput& in);  // validation.md section 4
Scene build_bar_impact(const SceneInput& in);     // validation.md section 3
Scene build_hertz(const SceneInput& in);          // validation.md section 6
Scene build_rack_pinion(const SceneInput& in);    // the paper's gear case
Scene build_tension_strip(const SceneInput& in);  // stability study: tensile instability

// Common helpers for builders.
void add_body(Simulation& sim, const std::string& name, const Material& material);
// Adds one particle to the last body (mass rho0 dx^2 per unit thickness, or
// rho0 * volume when a volume is given).
std::size_t add_particle(Simulation& sim, double x, double y, int motion, double volume = 0.0);
// Closes the last body's particle range.
void end_body(Simulation& sim);
// Domain: the particles' bounding box grown by `margin` on every side.
Box grown_bounds(const Particles& p, double margin);

}  // namespace gearsph::scenes
