#include <algorithm>

#include "solver/scene/builders.hpp"

namespace gearsph::scenes {

Material read_material(const nlohmann::json& m) {
  Material mat;
  mat.E = m.at("E_Pa").get<double>();
  mat.nu = m.at("nu").get<double>();
  mat.rho0 = m.at("rho_kg_m3").get<double>();
  return mat;
}

void add_body(Simulation& sim, const std::string& name, const Material& material) {
  Body b;
  b.name = name;
  b.material = material;
  b.begin = b.end = sim.particles.n;
  sim.bodies.push_back(b);
}

std::size_t add_particle(Simulation& sim, double x, double y, int motion, double volume) {
  const Material& mat = sim.bodies.back().material;
  const double dx = sim.discretization.dx;
  const std::size_t i = sim.particles.n;
  const double v = volume > 0.0 ? volume : dx * dx;
  sim.particles.add(x, y, mat.rho0 * v, mat.rho0, static_cast<int>(sim.bodies.size() - 1), motion);
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

}  // namespace gearsph::scenes
