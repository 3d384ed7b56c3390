#include "solver/physics/crack_face_contact.hpp"

#include <cmath>

#include "solver/physics/simulation.hpp"

namespace gearsph::physics {

namespace {

// Facing pairs reach at most this many spacings across the crack: a
// lattice's mirror neighbour (1) and its diagonal ones (sqrt 2), not the
// kernel's longer pairs, whose closure mixes in the faces' sliding.
constexpr double kFaceReach = 1.5;

}  // namespace

std::vector<CrackFacePair> crack_face_pairs(const Simulation& sim,
                                            const std::vector<CutPair>& cut) {
  const Particles& p = sim.particles;
  std::vector<CrackFacePair> faces;
  std::vector<double> gaps(p.n, 0.0);  // G: per particle, its pairs' reference gaps summed
  for (const CutPair& c : cut) {
    const double dx = 0.5 * (p.spacing[c.i] + p.spacing[c.j]);
    const double rx = p.x0[c.j] - p.x0[c.i], ry = p.y0[c.j] - p.y0[c.i];
    if (rx * rx + ry * ry > kFaceReach * kFaceReach * dx * dx) continue;
    const double gap = rx * c.nx + ry * c.ny;
    faces.push_back({c.i, c.j, c.nx, c.ny, gap, 0.0});
    gaps[c.i] += gap;
    gaps[c.j] += gap;
  }
  for (CrackFacePair& f : faces) {
    const Material& m = sim.material_of(f.i);
    const double e_prime = m.E / (1.0 - m.nu * m.nu);  // plane strain
    const double dx = 0.5 * (p.spacing[f.i] + p.spacing[f.j]);
    f.stiffness = e_prime * dx / (0.5 * (gaps[f.i] + gaps[f.j]));
  }
  return faces;
}

double crack_face_force(const Simulation& sim, const CrackFacePair& f) {
  const Particles& p = sim.particles;
  const double g = (p.x[f.j] - p.x[f.i]) * f.nx + (p.y[f.j] - p.y[f.i]) * f.ny;
  return g < f.gap ? f.stiffness * (f.gap - g) : 0.0;  // open: no tension across
}

std::size_t crack_face_contact(Simulation& sim) {
  Particles& p = sim.particles;
  std::size_t closed = 0;
  for (const CrackFacePair& f : sim.reference.faces) {
    const double g = (p.x[f.j] - p.x[f.i]) * f.nx + (p.y[f.j] - p.y[f.i]) * f.ny;
    if (g >= f.gap) continue;  // open, or just touching: no tension across
    const double force = f.stiffness * (f.gap - g);
    p.ext_ax[f.i] -= force * f.nx / p.mass[f.i];
    p.ext_ay[f.i] -= force * f.ny / p.mass[f.i];
    p.ext_ax[f.j] += force * f.nx / p.mass[f.j];
    p.ext_ay[f.j] += force * f.ny / p.mass[f.j];
    ++closed;
  }
  return closed;
}

double crack_face_energy(const Simulation& sim) {
  const Particles& p = sim.particles;
  double stored = 0.0;
  for (const CrackFacePair& f : sim.reference.faces) {
    const double g = (p.x[f.j] - p.x[f.i]) * f.nx + (p.y[f.j] - p.y[f.i]) * f.ny;
    if (g < f.gap) stored += 0.5 * f.stiffness * (f.gap - g) * (f.gap - g);
  }
  return stored;
}

}  // namespace gearsph::physics
